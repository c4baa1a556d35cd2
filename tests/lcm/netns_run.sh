#!/bin/sh
# Runs a command inside a private network namespace whose loopback carries multicast, so udpm://
# traffic (ttl=0) never leaves the test. Exit 77 (ctest: skipped) when namespaces are unavailable.
if ! unshare --net true 2>/dev/null; then
  echo "SKIP: cannot create a network namespace (unshare --net needs root or user namespaces)" >&2
  exit 77
fi
exec unshare --net sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo && exec "$@"' netns "$@"
