# Debian's packages through a private apt state (sourced): its own sources
# list, written here, its own lists and cache, and an empty dpkg status, so
# that apt resolves from the suites named alone, whatever the host runs.
# The host's apt and dpkg are left alone; nothing is installed.
#
#   debian_apt_init DIR ARCHS SUITE  the state in DIR (made when missing,
#                        locked until the caller exits) for the architectures
#                        ARCHS ("amd64", "arm64 amd64": the first is native)
#                        and SUITE (bookworm, trixie) with its -updates,
#                        -backports (from the archive the host uses,
#                        scripts/debian-mirror) and -security
#   debian_apt_lists     fetch the lists unless fetched within a day
#   debian_apt_update    fetch the lists now
#   debian_apt get|cache ARGS...         apt-get or apt-cache on the state
#   debian_apt_download DIR PACKAGE...   the .debs into DIR
#
# The sourcing script sets $top (the project) and defines fail().
# shellcheck shell=sh disable=SC2154

debian_apt_init() {
	dapt=$1
	dapt_archs=$2
	_suite=$3
	"$top/scripts/ensure-packages" apt dpkg debian-archive-keyring
	mkdir -p "$dapt/lists/partial" "$dapt/archives/partial" "$dapt/parts"
	exec 8>"$dapt/lock"
	flock 8
	[ -f "$dapt/status" ] || : >"$dapt/status"
	_mirror=$("$top/scripts/debian-mirror")
	_security=$("$top/scripts/debian-mirror" security)
	_options="arch=$(echo "$dapt_archs" | tr ' ' ,)"
	_options="$_options signed-by=/usr/share/keyrings/debian-archive-keyring.gpg"
	{
		for _part in "" -updates -backports; do
			echo "deb [$_options] $_mirror $_suite$_part main"
		done
		echo "deb [$_options] $_security $_suite-security main"
	} >"$dapt/sources.list.new"
	# Lists fetched for other sources are refetched.
	cmp -s "$dapt/sources.list.new" "$dapt/sources.list" || rm -f "$dapt/updated"
	mv "$dapt/sources.list.new" "$dapt/sources.list"
}

debian_apt_opts() {
	echo "-q -o APT::Architecture=${dapt_archs%% *}"
	for _arch in $dapt_archs; do echo "-o APT::Architectures::=$_arch"; done
	echo "-o Dir::Etc::SourceList=$dapt/sources.list" \
		"-o Dir::Etc::SourceParts=$dapt/parts" \
		"-o Dir::Etc::Preferences=$dapt/preferences" \
		"-o Dir::Etc::PreferencesParts=$dapt/parts" \
		"-o Dir::State::Lists=$dapt/lists -o Dir::State::status=$dapt/status" \
		"-o Dir::Cache=$dapt -o Dir::Cache::archives=$dapt/archives" \
		"-o Acquire::IndexTargets::deb::DEP-11::DefaultEnabled=false" \
		"-o Acquire::IndexTargets::deb::DEP-11-icons::DefaultEnabled=false" \
		"-o Acquire::IndexTargets::deb::DEP-11-icons-small::DefaultEnabled=false" \
		"-o Acquire::IndexTargets::deb::Contents-deb::DefaultEnabled=false" \
		"-o Acquire::Languages=none -o Debug::NoLocking=1"
	# The build tree is usually not readable by apt's sandbox user.
	[ "$(id -u)" -ne 0 ] || echo "-o APT::Sandbox::User=root"
}

# shellcheck disable=SC2046
debian_apt() {
	_tool=apt-$1
	shift
	"$_tool" $(debian_apt_opts) "$@"
}

debian_apt_update() {
	debian_apt get update >"$dapt/update.log" 2>&1 ||
		{ cat "$dapt/update.log" >&2; fail "apt-get update failed ($dapt)"; }
	touch "$dapt/updated"
}

# A day-old list may miss a new kernel ABI; within the day, a run fetches
# nothing.
debian_apt_lists() {
	[ -n "$(find "$dapt/updated" -mmin -1440 2>/dev/null)" ] || debian_apt_update
}

debian_apt_download() {
	_dir=$1
	shift
	(cd "$_dir" && debian_apt get download "$@" >/dev/null)
}
