#!/usr/bin/env bash
# Writes into OUT_DIR everything the code generator prints, so that a refactor of generator/ can
# be checked to change no output: `diff -r BEFORE AFTER` must be empty.
#   scripts/codegen_snapshot.sh BUILD_DIR OUT_DIR
# BUILD_DIR holds apps/boxgen (and apps/boxrecon, for the filter cache's sources). It emits:
# - every registry filter for every target (C++ and prefilters, GLSL float and double, CUDA) with
#   its --report, as text and JSON;
# - m7 with every strategy that applies to it, and tricubic with separable;
# - two SPECs that are not in the registry (the 2-D zp element, and a five-direction 3-D spline
#   on BCC) on every target;
# - registry.hpp;
# - the JSON of the commands that share the front end (presets, analyze, prefilter, bbform, pieces,
#   autocorr, eval);
# - the source of a SPEC filter the loader writes into its cache (C++ glue, GLSL float and double).
set -euo pipefail
build=$(cd "$1" && pwd)
out=$2
boxgen=$build/apps/boxgen
boxrecon=$build/apps/boxrecon
rm -rf "$out"
mkdir -p "$out"
cd "$out"

emit_all() {  # name spec [boxgen options...]
  local name=$1 spec=$2
  shift 2
  mkdir -p "$name/cpp" "$name/glsl" "$name/glsl-double" "$name/cuda"
  "$boxgen" emit "$spec" "$@" --name "$name" --out "$name/cpp" --report > "$name/report.txt"
  "$boxgen" emit "$spec" "$@" --name "$name" --out "$name/cpp" --report --json > "$name/report.json"
  "$boxgen" emit "$spec" "$@" --name "$name" --target glsl --out "$name/glsl" > /dev/null
  "$boxgen" emit "$spec" "$@" --name "$name" --target glsl --precision double \
    --out "$name/glsl-double" > /dev/null
  "$boxgen" emit "$spec" "$@" --name "$name" --target cuda --out "$name/cuda" > /dev/null
}

for f in m7 m8 m12 fcc6 tricubic cart7; do emit_all "$f" "$f" --strategy auto; done
for s in horner shifted bernstein monomial; do
  mkdir -p "strategy/m7-$s"
  "$boxgen" emit m7 --strategy "$s" --name m7 --out "strategy/m7-$s" --report --json \
    > "strategy/m7-$s/report.json"
  "$boxgen" emit m7 --strategy "$s" --name m7 --target glsl --out "strategy/m7-$s" > /dev/null
done
mkdir -p strategy/tricubic-separable
"$boxgen" emit tricubic --strategy separable --name tricubic --out strategy/tricubic-separable \
  --report --json > strategy/tricubic-separable/report.json
emit_all zp zp
emit_all five "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0" --lattice bcc
emit_all fcc6_shells fcc6 --shells 0
mkdir -p registry
for f in m7 m8 m12 fcc6 tricubic cart7; do cp "$f"/cpp/*.hpp registry/; done
"$boxgen" emit --registry m7,m8,m12,fcc6,tricubic,cart7 --out registry > /dev/null
find registry -name '*.hpp' ! -name registry.hpp -delete

mkdir -p json
"$boxgen" presets --json > json/presets.json
for f in m7 zp; do
  "$boxgen" analyze "$f" --json > "json/analyze-$f.json"
  "$boxgen" prefilter "$f" --shells 0,1 --json > "json/prefilter-$f.json"
  "$boxgen" bbform "$f" --json > "json/bbform-$f.json"
  "$boxgen" pieces "$f" --json > "json/pieces-$f.json"
done
"$boxgen" autocorr m7 --json > json/autocorr-m7.json
"$boxgen" eval m7 --at "1/4 1/2 1/8" --json > json/eval-m7.json

# Times measured by the commands are not output to compare.
for f in json/*.json; do
  /usr/bin/python3 -c '
import json, sys
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if not k.endswith("seconds")}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x
path = sys.argv[1]
data = strip(json.load(open(path)))
json.dump(data, open(path, "w"), indent=2, sort_keys=True)
' "$f"
done

# The loader's cache entry of a SPEC filter (its C++ source and GLSL; the shared object embeds
# paths and is not compared) and the values of the CPU and GL devices for it and for m7.
if [ -x "$boxrecon" ]; then
  spec="1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0"
  mkdir -p cache values
  export BOXGEN_CACHE_DIR=$out/cache-work
  printf '0.1 0.2 0.3\n-0.25 0.5 0.125\n0 0 0\n0.7 -0.3 0.05\n' > values/points.txt
  "$boxrecon" sample --filter "$spec" --lattice bcc --n 12 --quiet -o values/spec.nrrd > /dev/null
  "$boxrecon" sample --n 12 -o values/m7.nrrd > /dev/null
  for device in cpu gl; do
    "$boxrecon" eval --filter "$spec" --lattice bcc --quiet --volume values/spec.nrrd \
      --points values/points.txt --gradient --hessian --device $device > "values/spec-$device.txt"
    "$boxrecon" eval --filter m7 --volume values/m7.nrrd --points values/points.txt --gradient \
      --hessian --device $device > "values/m7-$device.txt"
  done
  # The entry's key hashes the runtime archive's time: the files get stable names and the key in
  # their text (the functions' prefix spec_KEY, the stamp) becomes KEY.
  for f in cache-work/*.cpp cache-work/*.glsl; do
    key=$(basename "$f" | sed 's/[._].*//')
    sed "s/$key/KEY/g" "$f" > "cache/$(basename "$f" | sed "s/$key/spec/")"
  done
  rm -rf cache-work values/*.nrrd
fi
