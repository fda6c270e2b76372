#!/bin/sh
# Run the shared conformance cases (../shared/conformance) and fail on any
# failure except the cases listed in tests/shared-pending.txt, which need
# work of a later issue; a pending case that passes is a failure too (it is
# to come off the list), so the list is kept honest.
#   sh tests/shared.sh S42 SHARED
s42=$1
shared=$2
. "$(dirname "$0")/lib.sh"
t_init shared
out=$(python3 "$shared/conformance/run.py" --s42 "$s42" "$shared/conformance/cases" 2>&1)
echo "$out" | grep -v '^ok '
pending=$(grep -v '^#' tests/shared-pending.txt 2>/dev/null | awk '{print $1}')
skip=0
for name in $(echo "$out" | awk '/^ok /{print $2}'); do
  if echo "$pending" | grep -qx "$name"; then
    bad "$name passes now: remove it from tests/shared-pending.txt"
  else
    ok
  fi
done
for name in $(echo "$out" | awk '/^FAIL /{sub(":", "", $2); print $2}'); do
  if echo "$pending" | grep -qx "$name"; then
    skip=$((skip + 1))
  else
    T_FAIL=$((T_FAIL + 1))       # run.py printed its FAIL line above
  fi
done
echo "$out" | grep -q '^[0-9]* passed, [0-9]* failed$' || bad "run.py did not finish: $(echo "$out" | tail -3)"
t_done ", $skip skipped"
