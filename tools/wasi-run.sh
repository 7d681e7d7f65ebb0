#!/bin/sh
# The wasm32-wasip1 test runner (.cargo/config.toml): Node with tools/wasi-run.mjs, found next to
# this script, so it works from any package's directory (cargo runs tests in the package's own).
# --no-turbo-fast-api-calls: Node 20's WASI fast calls keep using the module's memory after
# `memory.grow` has moved it (nodejs/node#53087), which segfaults node at exit (or drops
# output) once a test has grown the heap enough, e.g. the envmap tests' sample batches.
exec node --no-warnings --no-turbo-fast-api-calls --stack-size=4000 "$(dirname "$0")/wasi-run.mjs" "$@"
