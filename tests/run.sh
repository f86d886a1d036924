#!/usr/bin/env bash
# Install what the tests need (Python packages; Debian's chromium, poppler-utils, postgresql and nginx when missing), then run the whole suite.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore -e ".[test]" -c .ci/constraints.txt
if ! command -v /usr/bin/chromium >/dev/null 2>&1; then
    if [ "$(id -u)" -eq 0 ]; then apt-get update -qq && apt-get install -y -qq chromium >/dev/null
    else sudo apt-get update -qq && sudo apt-get install -y -qq chromium >/dev/null; fi
fi
if ! command -v pdftotext >/dev/null 2>&1; then     # tests/browser/test_project_report.py reads the printed PDF
    if [ "$(id -u)" -eq 0 ]; then apt-get update -qq && apt-get install -y -qq poppler-utils >/dev/null
    else sudo apt-get update -qq && sudo apt-get install -y -qq poppler-utils >/dev/null; fi
fi
if ! command -v initdb >/dev/null 2>&1 && ! ls /usr/lib/postgresql/*/bin/initdb >/dev/null 2>&1; then
    # a real PostgreSQL for the store tests (tests/postgres.py starts its own server in a temporary directory)
    if [ "$(id -u)" -eq 0 ]; then apt-get update -qq && apt-get install -y -qq postgresql >/dev/null
    else sudo apt-get update -qq && sudo apt-get install -y -qq postgresql >/dev/null; fi
fi
if ! command -v nginx >/dev/null 2>&1 && [ ! -x /usr/sbin/nginx ]; then     # tests/test_deployment.py
    if [ "$(id -u)" -eq 0 ]; then apt-get update -qq && apt-get install -y -qq nginx >/dev/null
    else sudo apt-get update -qq && sudo apt-get install -y -qq nginx >/dev/null; fi
fi
mkdir -p test-artifacts
# the suite starts about a hundred servers and many more Python processes: each would compile the app's modules
# from source again (~0.5 CPU-s) where the environment forbids writing bytecode, so it is written here, once
unset PYTHONDONTWRITEBYTECODE
python3 -m compileall -q -j 0 server tests bench
python3 -m server.core.warm_up     # compile the numba kernels once into their disk cache (tens of seconds when new)
# four worker processes on two CPUs: the browser and server tests mostly wait (pages settling, servers starting),
# the numeric ones fill the gaps; the tests sharing a module's own fixture stay on one worker (tests/conftest.py)
if [ "$#" -gt 0 ]; then exec python3 -m pytest -q --durations=15 -n 4 --dist loadgroup "$@"; fi
before=$(python3 tests/leftover_processes.py --snapshot)
# test_schemathesis_api's last test counts what the module's operation tests sent (module state): schemathesis's
# items do not take xdist's group, so the module runs in a process of its own, beside the others (its output
# follows theirs). Both runs run; the suite fails if either did, or if a test left a process behind.
status=0
python3 -m pytest -q -p no:xdist -p no:cacheprovider tests/test_schemathesis_api.py > test-artifacts/schemathesis.log 2>&1 &
fuzzing=$!
python3 -m pytest -q --durations=15 -n 4 --dist loadgroup --junitxml=test-artifacts/junit.xml --ignore=tests/test_schemathesis_api.py || status=$?
wait "$fuzzing" || status=$((status ? status : $?))
cat test-artifacts/schemathesis.log
python3 tests/leftover_processes.py --since "$before" || status=$((status ? status : 1))
exit "$status"
