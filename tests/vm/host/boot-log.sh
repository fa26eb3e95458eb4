# Reading the output of a vm-run boot of several scripts, for its callers
# (tests/vm/vmtest, tests/upstream/upstream-check); sourced by bash.

# boot_log_section LOG NAME: the part of the output that is script NAME's,
# and vm-run's own lines.
boot_log_section() {
	awk -v n="$2" '
		$0 ~ "^==vm-run== scenario " n " begin" { inside = 1 }
		inside || /^vm-run:/ { print }
		$0 ~ "^==vm-run== scenario " n " exit status" { inside = 0 }' "$1"
}

# boot_log_seconds LOG NAME: the seconds script NAME ran, by the guest's
# clock; nothing when it did not end.
boot_log_seconds() {
	awk -v n="$2" '
		$0 ~ "^==vm-run== scenario " n " begin at" { b = $(NF - 1) }
		b != "" && /^==vm-run== scenario done at/ { printf "%d", $(NF - 1) - b; exit }' "$1"
}

# boot_log_passed LOG NAME: whether vm-run judged script NAME passed.
boot_log_passed() {
	grep -q "^vm-run: result $2 PASS\$" "$1"
}
