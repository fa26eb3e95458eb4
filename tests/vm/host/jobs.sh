# Running the jobs tests/vm/vmtest planned (job_kind, job_kernel, job_log,
# job_entries, job_args and job_cpu, indexed alike) in the background, as
# many at once as VM_JOBS (max_jobs) and the CPU budget (cpu_budget, in
# percent of a core) allow; each leaves its verdict, cost and share of a
# core in the directory $verdicts, for vmtest to count and record.
# Sourced by bash.

result() { # kernel name verdict seconds
	printf '%-8s %-36s %s\n' "$1" "$2" "$3"
}

# print_result KERNEL LABEL VERDICT [LOG]: one line, and a failure's log
# tail, under a lock so that two runs ending together do not interleave.
print_result() {
	{
		flock 9
		result "$1" "$2" "$3"
		[ -z "${4:-}" ] || tail -n 60 "$4" | sed 's/^/    | /'
	} 9>>"$verdicts/print.lock"
}

# run ID KERNEL LABEL LOG COMMAND...: one run of a command that is a test
# of its own (the self-test), in the background.
run() {
	local id=$1 kernel=$2 label=$3 log=$4 t0
	shift 4
	t0=$(date +%s)
	if "$@" >"$log" 2>&1; then
		echo "PASS $kernel/$label" >"$verdicts/$id"
		echo "$kernel $label $(( $(date +%s) - t0 ))" >"$verdicts/cost-$id"
		print_result "$kernel" "$label" "PASS ($(( $(date +%s) - t0 )) s)"
	else
		echo "FAIL $kernel/$label $log" >"$verdicts/$id"
		print_result "$kernel" "$label" "FAIL ($(( $(date +%s) - t0 )) s), log: $log" "$log"
	fi
}

# timed LOG COMMAND...: COMMAND, its output into LOG; prints the real, user
# and system seconds it took, its children's included.
timed() {
	local log=$1
	shift
	{ TIMEFORMAT='%R %U %S'; time "$@" >"$log" 2>&1 || true; } 2>&1 | tail -n 1
}

# record_cpu KERNEL ID "REAL USER SYS": a boot's share of a core, for the
# costs (a boot too short to tell gives none).
record_cpu() {
	echo "$3" | awk -v k="$1" '$1 > 10 { printf "%s (cpu) %d\n", k, 100 * ($2 + $3) / $1 }' \
		>"$verdicts/cpu-$2"
}

# run_boot KERNEL LOG "ID:LABEL..." COMMAND...: one vm-run boot of several
# scenarios, in the background; each gets its own verdict from vm-run's
# "result" lines, and its own log.  Its share of a core goes to the costs.
run_boot() {
	local kernel=$1 log=$2 entries=${3# } entry id label name secs boot times
	shift 3
	times=$(timed "$log" "$@")
	record_cpu "$kernel" "${entries%%:*}" "$times"
	# The boot's own time: vm-run's whole run less its scenarios'.
	boot=$(awk '/^==vm-run== scenario .* begin at/ { b = $(NF - 1) }
		/^==vm-run== scenario done at/ { s += $(NF - 1) - b }
		/^vm-run: .* exit status [0-9]+, [0-9.]+s$/ { e = $NF + 0 }
		END { if (e) printf "%d", e - s }' "$log")
	[ -z "$boot" ] || echo "$kernel (boot) $boot" >"$verdicts/cost-${entries%%:*}-boot"
	for entry in $entries; do
		id=${entry%%:*} label=${entry#*:} name=${label%%\[*}
		boot_log_section "$log" "$name" >"${log%/*}/$label.log"
		echo "(the whole boot: $log)" >>"${log%/*}/$label.log"
		secs=$(boot_log_seconds "$log" "$name")
		[ -z "$secs" ] || echo "$kernel $label $secs" >"$verdicts/cost-$id"
		if boot_log_passed "$log" "$name"; then
			echo "PASS $kernel/$label" >"$verdicts/$id"
			print_result "$kernel" "$label" "PASS (${secs:-?} s)"
		else
			echo "FAIL $kernel/$label ${log%/*}/$label.log" >"$verdicts/$id"
			print_result "$kernel" "$label" "FAIL (${secs:-?} s), log: ${log%/*}/$label.log" \
				"${log%/*}/$label.log"
		fi
	done
}

# run_extra KERNEL NAME LOG COMMAND...: a boot of another check, in the
# background; its time and share of a core go to the costs, its verdict is
# that check's.
run_extra() {
	local kernel=$1 name=$2 log=$3 times
	shift 3
	times=$(timed "$log" "$@")
	record_cpu "$kernel" "$name" "$times"
	echo "$kernel $name ${times%%.*}" >"$verdicts/cost-$name"
	print_result "$kernel" "$name" "ran (${times%%.*} s), for its own check: $log"
}

# The jobs started, by process id: their shares of a core.
declare -A job_share
# fits J: whether job J may start now, with the shares of the jobs still
# running (always, when none is).
fits() {
	local pid used=0 n=0
	for pid in $(jobs -rp); do
		used=$((used + ${job_share[$pid]:-0})) n=$((n + 1))
	done
	[ "$n" -eq 0 ] || { [ "$n" -lt "$max_jobs" ] && [ $((used + job_cpu[$1])) -le "$cpu_budget" ]; }
}

# start_job J: job J in the background.
start_job() {
	local j=$1
	if [ "${job_kind[j]}" = selftest ]; then
		run "${job_entries[j]%%:*}" "${job_kernel[j]}" rig-selftest "${job_log[j]}" \
			"$here/selftest/run" "${job_kernel[j]}" &
	elif [ "${job_kind[j]}" = extra ]; then
		read -r -a args <<<"${job_args[j]}"
		run_extra "${job_kernel[j]}" "${job_entries[j]}" "${job_log[j]}" "$here/vm-run" "${args[@]}" &
	else
		read -r -a args <<<"${job_args[j]}"
		run_boot "${job_kernel[j]}" "${job_log[j]}.log" "${job_entries[j]}" \
			"$here/vm-run" --kernel "${job_kernel[j]}" --logs "${job_log[j]}" "${args[@]}" &
	fi
	job_share[$!]=${job_cpu[j]}
}

# run_jobs J...: the jobs J, the first one that fits first, until all ran.
run_jobs() {
	local pending=("$@") i
	while [ ${#pending[@]} -gt 0 ]; do
		for i in "${!pending[@]}"; do
			fits "${pending[i]}" || continue
			start_job "${pending[i]}"
			unset "pending[i]"
			pending=("${pending[@]}")
			continue 2
		done
		wait -n || true
	done
	wait
}
