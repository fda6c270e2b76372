#!/bin/sh
# Run the shared conformance cases (../shared/conformance) and fail on any
# failure except the cases listed in tests/shared-pending.txt, which need
# work of a later issue; a pending case that passes is reported, so the list
# is kept honest.
#   sh tests/shared.sh S42 SHARED
s42=$1
shared=$2
out=$(python3 "$shared/conformance/run.py" --s42 "$s42" "$shared/conformance/cases" 2>&1)
echo "$out" | grep -v '^ok '
pending=$(grep -v '^#' tests/shared-pending.txt 2>/dev/null | awk '{print $1}')
pass=0; fail=0; skip=0; bad=0
for name in $(echo "$out" | awk '/^ok /{print $2}'); do
  pass=$((pass + 1))
  if echo "$pending" | grep -qx "$name"; then
    echo "shared: $name passes now: remove it from tests/shared-pending.txt"
    bad=1
  fi
done
for name in $(echo "$out" | awk '/^FAIL /{sub(":", "", $2); print $2}'); do
  if echo "$pending" | grep -qx "$name"; then
    skip=$((skip + 1))
  else
    fail=$((fail + 1))
  fi
done
echo "shared: $pass passed, $fail failed, $skip skipped"
[ "$fail" = 0 ] && [ "$bad" = 0 ]
