# Sourced by fetch-userland and fetch-kernel: Debian's arm64 packages
# through a private apt state under build/arm64/apt/.
#
# The host's own apt configuration is left alone (no foreign architecture
# is added, nothing is installed): the private state reads the host's
# sources for arm64 only, with an empty dpkg status so that apt resolves a
# whole dependency closure.  The sourcing script sets $top (the project)
# and $apt (the state's directory), and defines fail().
# shellcheck shell=sh

arm64_apt_init() {
	"$top/scripts/ensure-packages" apt dpkg
	mkdir -p "$apt/lists/partial" "$apt/archives/partial"
	[ -f "$apt/status" ] || : >"$apt/status"
}

apt_opts() {
	echo "-q -o APT::Architecture=arm64 -o APT::Architectures::=arm64" \
		"-o Dir::State::Lists=$apt/lists -o Dir::State::status=$apt/status" \
		"-o Dir::Cache=$apt -o Dir::Cache::archives=$apt/archives" \
		"-o Debug::NoLocking=1"
	[ "$(id -u)" -ne 0 ] || echo "-o APT::Sandbox::User=root"
}

# shellcheck disable=SC2046
apt_update() { apt-get $(apt_opts) update >"$apt/update.log" 2>&1 ||
	{ cat "$apt/update.log" >&2; fail "apt-get update for arm64 failed"; }; }

have_lists() { ls "$apt/lists"/*arm64_Packages* >/dev/null 2>&1; }

# apt_download DIR PACKAGE...: the .debs into DIR.
# shellcheck disable=SC2046
apt_download() {
	_dir=$1
	shift
	(cd "$_dir" && apt-get $(apt_opts) download "$@" >/dev/null)
}
