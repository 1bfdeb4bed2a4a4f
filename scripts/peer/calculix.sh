#!/usr/bin/env bash
# Side-by-side run of SDNV103 modelling B with aster and with CalculiX (ccx):
# same axisymmetric QUAD8 mesh, material, friction, initial velocity and time
# list. Installs ccx (Debian package calculix-ccx) and h5py when missing,
# builds our release binary, converts the MED mesh to a ccx deck
# (scripts/peer/med2ccx.py), runs both codes, prints B1 DX, A2 DY, wall times,
# increments and the time ratio. What the two models do differently, and what
# happened when ccx was run on this problem: docs/peer-calculix.md.
#
# Usage: scripts/peer/calculix.sh [--n1 N --n2 N] [--ccx-timeout S]
#                                 [--keep DIR] [-- med2ccx options...]
#   --n1/--n2      mesh (default 5 x 20, the mesh of the study, med/sdnv103b.mmed);
#                  any other size is generated with `aster mesh taylor` and
#                  given to both codes
#   --ccx-timeout  wall-time limit of the ccx run in seconds (default 900)
#   --keep DIR     work in DIR and keep it (default: a temporary directory)
#   after --        options passed to med2ccx.py (e.g. --auto, --contact face,
#                  --penalty 5.85e6, --alpha -0.05, --min-divisor 16)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
n1=5 n2=20 timeout_s=900 keep=""
conv=()
while [ $# -gt 0 ]; do
  case "$1" in
    --n1) n1="$2"; shift 2 ;;
    --n2) n2="$2"; shift 2 ;;
    --ccx-timeout) timeout_s="$2"; shift 2 ;;
    --keep) keep="$2"; shift 2 ;;
    --) shift; conv=("$@"); break ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "calculix.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done

# ---- tools
if ! command -v ccx >/dev/null 2>&1; then
  echo "calculix.sh: ccx missing, installing calculix-ccx" >&2
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq calculix-ccx >/dev/null
fi
python3 -c "import h5py" 2>/dev/null || python3 -m pip install --quiet h5py
(cd "$root" && cargo build --release --quiet)
aster="$root/target/release/aster"

# ---- work directory and mesh
if [ -n "$keep" ]; then work="$keep"; mkdir -p "$work"; else
  work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
mkdir -p "$work/aster" "$work/ccx"
if [ "$n1" = 5 ] && [ "$n2" = 20 ]; then
  mesh="$root/med/sdnv103b.mmed"
else
  mesh="$work/taylor_${n1}x${n2}.mmed"
  "$aster" mesh taylor --kind axis --n1 "$n1" --n2 "$n2" --output "$mesh" >/dev/null
fi
echo "mesh: $mesh ($n1 x $n2 QUAD8)" >&2

now() { date +%s.%N; }

# ---- aster: the study as it is, mesh on unit 20 (on another mesh the
# TEST_RESU non-regression values fail: exit 1 is expected, the values are read
# from the result table all the same)
cp "$root/comm/sdnv103b.comm" "$work/aster/sdnv103b.comm"
t0=$(now)
set +e
"$aster" run "$work/aster/sdnv103b.comm" --unit "20=$mesh" --unit "80=$work/aster/sdnv103b.rmed" \
  --out "$work/aster" --quiet >"$work/aster/stdout.txt" 2>&1
aster_rc=$?
set -e
t1=$(now)

# ---- ccx
python3 "$root/scripts/peer/med2ccx.py" "$mesh" "$work/ccx/sdnv103b.inp" "${conv[@]}"
t2=$(now)
set +e
(cd "$work/ccx" && OMP_NUM_THREADS=1 timeout "$timeout_s" ccx -i sdnv103b >ccx.log 2>&1)
ccx_rc=$?
set -e
t3=$(now)

python3 "$root/scripts/peer/report.py" \
  --aster-resu "$work/aster/sdnv103b.resu" --aster-rc "$aster_rc" \
  --aster-time "$t0" "$t1" \
  --ccx-dir "$work/ccx" --ccx-rc "$ccx_rc" --ccx-time "$t2" "$t3" \
  --ccx-timeout "$timeout_s"
[ -n "$keep" ] && echo "files kept in $work" >&2
exit 0
