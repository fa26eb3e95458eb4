# tests/lib/tally.sh: the PASS/FAIL lines and the totals of a host-side
# check script (sourced).  "tally NAME" prints NAME's totals last; its
# status fails the script when a check failed or none ran.
passed=0
failed=0
pass() { passed=$((passed + 1)); echo "  PASS  $1"; }
fail() { failed=$((failed + 1)); echo "  FAIL  $1"; }
tally() {
	echo "$1: $passed passed, $failed failed"
	[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
}
