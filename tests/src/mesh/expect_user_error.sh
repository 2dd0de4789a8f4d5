#!/usr/bin/env bash
# Usage: expect_user_error.sh REGEX [--absent PATH] -- COMMAND...
# Passes when COMMAND exits with code 2, prints exactly one line on stderr matching REGEX, and
# (with --absent) PATH does not exist afterwards (nothing half-written).
set -u
regex=$1; shift
absent=""
if [ "${1:-}" = "--absent" ]; then absent=$2; shift 2; fi
[ "${1:-}" = "--" ] && shift
err=$("$@" 2>&1 >/dev/null); rc=$?
echo "exit $rc, stderr: $err"
[ "$rc" -eq 2 ] || { echo "FAIL: exit code $rc, expected 2"; exit 1; }
[ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || { echo "FAIL: expected one line"; exit 1; }
printf '%s\n' "$err" | grep -Eq -- "$regex" || { echo "FAIL: does not match $regex"; exit 1; }
if [ -n "$absent" ] && [ -e "$absent" ]; then echo "FAIL: $absent exists"; exit 1; fi
exit 0
