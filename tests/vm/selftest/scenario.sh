#!/bin/sh
# Guest half of the rig self-test: provoke reports with rigcheck.ko, then
# exit with a status vm-run must hand back unchanged.
set -u
params="warn=1"
[ "$VM_KERNEL" != debug ] || params="$params lockdep=1 kasan=1 leak=1"
# shellcheck disable=SC2086
insmod /extra/rigcheck.ko $params || { echo "rigcheck: insmod failed"; exit 1; }
echo "rigcheck: loaded with $params"
exit 7
