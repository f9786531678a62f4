#!/usr/bin/env bash
# The SMPI build (docs/smpi.md) on 64 simulated hosts of the fat tree: the real strategies composite
# a 1024^2 frame of synthetic sphere layers (coverage 0.4) by direct send, binary-swap and radix-k
# (k = 4, 8). Checks: every strategy's frame equals direct send's within 1/255 and covers 0.4 of
# the frame (bench_scale --check); the simulated times include the charged compute (direct send's
# rank 0 decodes and blends every layer pixel, so it cannot take less than that many pixels at the
# measured rate); radix-k (k = 8) beats direct send at 64 hosts, as it does on real clusters;
# `auto` (forecasting with the platform's network) chooses a strategy within 10 % of the best of
# the six and takes that strategy's time.
# Skips (77) where SimGrid is not installed.
# Usage: smpi_64.sh BENCH_SCALE_SMPI SOURCE_DIR
set -euo pipefail
bench=$1 root=$2
if ! command -v smpirun >/dev/null || [ -z "$bench" ] || [ ! -x "$bench" ]; then
  echo "SKIPPED: no SMPI build: SimGrid's smpicxx/smpirun are not installed (apt-get install" \
       "libsimgrid-dev; scripts/install-deps installs it, then re-run cmake), or -DSORTLAST_SMPI=OFF"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rates=$root/results/scale/rates.csv
net=$(python3 "$root/scripts/scale_platform.py" fattree 64 "$tmp/p.xml" --hostfile "$tmp/h.txt" --print-network)
"$root/scripts/smpi-run" "$tmp/p.xml" "$tmp/h.txt" 64 "$bench" --rates "$rates" --sizes 1024 \
  --coverage 0.4 --reps 1 --warmup 0 --network "$net" \
  --strategies direct,binary-swap,radix-k:4,radix-k:8,radix-k:16,radix-k:32,auto \
  --platform fattree --header --check >"$tmp/out.csv"
cat "$tmp/out.csv"
python3 - "$tmp/out.csv" "$rates" <<'PY'
import csv, sys
rows = {r["strategy"] + ("" if r["strategy"] == "auto" else r["radix"]): r
        for r in csv.DictReader(open(sys.argv[1]))}
rate = next(float(l.split(",")[2]) for l in open(sys.argv[2]) if l.startswith("decode_blend8,4,"))
assert set(rows) == {"direct", "binary-swap2", "radix-k4", "radix-k8", "radix-k16", "radix-k32",
                     "auto"}, rows.keys()
auto = rows.pop("auto")
chose = auto["radix"].split(":")  # auto:NAME[:k]
name = chose[1] + (chose[2] if len(chose) > 2 else "")
best = min(rows, key=lambda n: float(rows[n]["seconds"]))
t, tb = float(auto["seconds"]), float(rows[best]["seconds"])
print(f"auto chose {name}: {t:.4f} s; best {best} {tb:.4f} s")
assert abs(t / float(rows[name]["seconds"]) - 1) < 0.01, "auto's time is not its choice's"
assert t <= 1.10 * tb, "auto is more than 10 % behind the best strategy"
d = rows["direct"]
floor = float(d["layer_pixels"]) * rate * 1e-9
print(f"direct send {float(d['seconds']):.4f} s >= {floor:.4f} s of decode+blend at {rate} ns/pixel")
assert float(d["seconds"]) >= floor, "the charged compute is missing from the simulated time"
k8 = float(rows["radix-k8"]["seconds"])
print(f"radix-k (k = 8) {k8:.4f} s < direct send {float(d['seconds']):.4f} s")
assert k8 < float(d["seconds"])
for r in rows.values():
    assert int(r["ranks"]) == 64 and float(r["bytes_sent"]) > 0 and int(r["active_ranks"]) > 0, r
print("scale: ok")
PY
