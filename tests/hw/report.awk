# The kit's report (run by mcp2510-hwtest): reads results.txt (lib.sh
# says its lines), prints the table and writes -v json=FILE in the shape
# of make bench's summary.json: {DRIVER: {chip, rx_loss, ...}, setup}.
# Numbers stay numbers, a missing figure ("-") is null.

function q(s) { gsub(/\\/, "\\\\", s); gsub(/"/, "\\\"", s); gsub(/\t/, " ", s); return "\"" s "\"" }
function num(v) { return (v == "-" || v == "") ? "null" : v + 0 }
function rest(from,   s, i) { s = $from; for (i = from + 1; i <= NF; i++) s = s " " $i; return s }

$1 == "info" { key = $2; infos[key] = rest(3); order[++ninfo] = key; next }
$1 == "check" {
	n = ++nchecks; cname[n] = $2; cverdict[n] = $3; cdetail[n] = rest(4)
	count[$3]++
	next
}
$1 == "flood" {
	n = ++nfloods; fdir[n] = $2; frate[n] = $3
	for (i = 4; i <= NF; i++) { split($i, kv, "="); fv[n, kv[1]] = kv[2]; if (n == 1) fkeys[++nkeys] = kv[1] }
	next
}

$1 == "transit" {
	n = ++ntransits; tdir[n] = $2; trate[n] = $3
	for (i = 4; i <= NF; i++) { split($i, kv, "="); tv[n, kv[1]] = kv[2] }
	next
}

function rate_map(key, worst,   s, n, r, v, seen, out) {
	# per bit rate, the worse of the two directions
	for (n = 1; n <= nfloods; n++) {
		r = frate[n]; v = (key == "rx_loss") ? fv[n, "lost"] / fv[n, "frames"] : fv[n, key]
		if (!(r in seen) || (worst == "max" && v > seen[r]) || (worst == "min" && v < seen[r])) seen[r] = v
	}
	s = ""
	for (n = 1; n <= nfloods; n++) {
		r = frate[n]
		if ((r in seen) && !(r in out)) { s = s (s ? ", " : "") q(r) ": " sprintf("%.4f", seen[r]); out[r] = 1 }
	}
	return "{" s "}"
}

END {
	a = infos["interfaces"]
	split(a, ifs, " ")
	drv = infos[ifs[1] ".driver"]; chip = infos[ifs[1] ".chip"]
	printf "\nmcp2510-hwtest report: %s on %s, kernel %s, %s\n", drv, chip, infos["kernel"], infos["board"]
	printf "driver version %s, oscillator %s Hz, SPI at most %s Hz\n\n", infos[ifs[1] ".driver_version"],
		infos[ifs[1] ".oscillator_hz"], infos[ifs[1] ".spi_max_hz"]
	printf "%-22s %-5s %s\n", "check", "", "detail"
	for (n = 1; n <= nchecks; n++) printf "%-22s %-5s %s\n", cname[n], cverdict[n], cdetail[n]
	printf "\n%-12s %8s %7s %5s %5s %5s %5s %5s %6s %5s %6s %11s %11s\n", "flood", "bitrate", "recv", "lost", "ovf", "dup",
		"reord", "corr", "util", "cpu%", "irq/f", "spi xf/f", "spi B/f"
	for (n = 1; n <= nfloods; n++)
		printf "%-12s %8s %7s %5s %5s %5s %5s %5s %6s %5s %6s %11s %11s\n", fdir[n], frate[n], fv[n, "received"],
			fv[n, "lost"], fv[n, "rx_over_errors"], fv[n, "duplicated"], fv[n, "reordered"], fv[n, "corrupted"], fv[n, "utilisation"],
			fv[n, "cpu_busy_pct"], fv[n, "irqs_per_frame"],
			fv[n, "rx_spi_transfers_per_frame"] "/" fv[n, "tx_spi_transfers_per_frame"],
			fv[n, "rx_spi_bytes_per_frame"] "/" fv[n, "tx_spi_bytes_per_frame"]
	printf "\n(ovf: the receiver's rx_over_errors; spi: receiving / sending side's SPI device, - where\n"
	printf "the kernel keeps no statistics; utilisation counts no stuff bits)\n"
	printf "\n%-12s %8s %7s %5s %7s %9s %9s %9s\n", "latency", "bitrate", "recv", "lost", "damaged",
		"median us", "99% us", "max us"
	for (n = 1; n <= ntransits; n++)
		printf "%-12s %8s %7s %5s %7s %9s %9s %9s\n", tdir[n], trate[n], tv[n, "received"], tv[n, "lost"],
			tv[n, "damaged"], tv[n, "median_us"], tv[n, "p99_us"], tv[n, "max_us"]
	printf "(lone frames, from write() on one interface to recvmsg() on the other)\n"
	printf "checks: %d passed, %d failed, %d not run, %d not offered by the driver\n",
		count["pass"], count["fail"], count["skip"], count["n/a"]

	if (json == "") exit
	o = "{\n  " q(drv) ": {\n    \"chip\": " q(chip) ",\n"
	o = o "    \"verdict\": " q(count["fail"] ? "fail" : "pass") ",\n"
	o = o "    \"rx_loss\": " rate_map("rx_loss", "max") ",\n"
	o = o "    \"tx_bus_utilisation\": " rate_map("utilisation", "min") ",\n"
	o = o "    \"cpu_busy_pct\": " rate_map("cpu_busy_pct", "max") ",\n"
	# the per-frame costs of the first (slowest) flood, as the bench's
	split("rx_spi_bytes_per_frame rx_spi_transfers_per_frame tx_spi_bytes_per_frame tx_spi_transfers_per_frame irqs_per_frame", per, " ")
	for (i = 1; i <= 5; i++) o = o "    " q(per[i]) ": " (nfloods ? num(fv[1, per[i]]) : "null") ",\n"
	o = o "    \"latency_us\": {"
	for (n = 1; n <= ntransits; n++)
		o = o (n > 1 ? ", " : "") q(trate[n]) ": {\"median\": " num(tv[n, "median_us"]) ", \"p99\": " \
			num(tv[n, "p99_us"]) ", \"max\": " num(tv[n, "max_us"]) ", \"lost\": " num(tv[n, "lost"]) "}"
	o = o "},\n"
	o = o "    \"floods\": ["
	for (n = 1; n <= nfloods; n++) {
		o = o (n > 1 ? "," : "") "\n      {\"direction\": " q(fdir[n]) ", \"bitrate\": " frate[n]
		for (k = 1; k <= nkeys; k++) o = o ", " q(fkeys[k]) ": " num(fv[n, fkeys[k]])
		o = o "}"
	}
	o = o "\n    ],\n    \"checks\": {"
	for (n = 1; n <= nchecks; n++)
		o = o (n > 1 ? "," : "") "\n      " q(cname[n]) ": {\"verdict\": " q(cverdict[n]) ", \"detail\": " q(cdetail[n]) "}"
	o = o "\n    }\n  },\n  \"setup\": {"
	for (n = 1; n <= ninfo; n++) {
		v = infos[order[n]]
		o = o (n > 1 ? "," : "") "\n    " q(order[n]) ": " (v ~ /^[0-9]+$/ ? v : q(v))
	}
	o = o "\n  }\n}\n"
	printf "%s", o >json
	close(json)
}
