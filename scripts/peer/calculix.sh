#!/usr/bin/env bash
# Side-by-side run of SDNV103 modelling B with aster and with CalculiX (ccx):
# same axisymmetric QUAD8 mesh, material, initial velocity and number of
# increments. Installs ccx (Debian package calculix-ccx) and h5py when missing,
# builds our release binary, converts the MED mesh to a ccx deck
# (scripts/peer/med2ccx.py), runs both codes, prints B1 DX, A2 DY, wall times,
# increments and the time ratio. What the two models do differently, and what
# happened when ccx was run on this problem: docs/peer-calculix.md.
#
# Usage: scripts/peer/calculix.sh [--setup friction|gap|direct] [--n1 N --n2 N]
#                                 [--ccx-timeout S] [--keep DIR]
#                                 [-- med2ccx options...]
#   --setup friction (default) the study as it is in both codes: ccx
#                    node-to-surface contact with Coulomb 0.25, penalty 1e7
#                    MPa/mm, automatic increments (ccx's contact rules make them
#                    ~1e-8 s: about 5800 increments, ~10 min for ccx)
#   --setup gap      the impact face held by frictionless GAPUNI supports (not
#                    contact elements for ccx: ~200 increments, ~30 s); aster
#                    runs the study WITHOUT friction (a copy of
#                    comm/sdnv103b.comm with the Coulomb keywords removed), so
#                    both codes solve the same frictionless problem
#   --setup direct   the first attempt: node-to-surface contact with friction,
#                    penalty 1e8, our 163 fixed increments (ccx stops at the
#                    impact: docs/peer-calculix.md)
#   --n1/--n2      mesh (default 5 x 20, the mesh of the study, med/sdnv103b.mmed);
#                  any other size is generated with `aster mesh taylor` and
#                  given to both codes
#   --ccx-timeout  wall-time limit of the ccx run in seconds (default 900)
#   --keep DIR     work in DIR and keep it (default: a temporary directory)
#   after --        more options for med2ccx.py, after those of the setup (e.g.
#                  --alpha -0.05, --gap-stiffness 1e10, --penalty 1e7, --auto,
#                  --touch, --min-divisor 1000; see med2ccx.py --help)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
n1=5 n2=20 timeout_s=900 keep="" setup=friction
conv=()
while [ $# -gt 0 ]; do
  case "$1" in
    --setup) setup="$2"; shift 2 ;;
    --n1) n1="$2"; shift 2 ;;
    --n2) n2="$2"; shift 2 ;;
    --ccx-timeout) timeout_s="$2"; shift 2 ;;
    --keep) keep="$2"; shift 2 ;;
    --) shift; conv=("$@"); break ;;
    -h|--help) sed -n '2,30p' "$0"; exit 0 ;;
    *) echo "calculix.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
case "$setup" in
  # The increment that starts at first touch (--touch) keeps ccx's energy
  # check from seeing an impact loss; automatic increments let its contact
  # rules pick the size; a penalty of 1e8 makes them 3 times smaller than
  # 1e7 and 1e6 trips the check again (docs/peer-calculix.md).
  friction) conv=(--contact node --penalty 1e7 --touch --auto --min-divisor 1000
                  "${conv[@]}") ;;
  # GAPUNI elements are not contact elements for ccx, so its impact rule
  # never applies; the patient Newton controls let a closing gap iterate.
  gap) conv=(--contact gap --touch --auto --min-divisor 1000
             --controls 20,30,9,50,10,4,,5 "${conv[@]}") ;;
  direct) ;;
  *) echo "calculix.sh: --setup is friction, gap or direct, not $setup" >&2; exit 2 ;;
esac

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
if [ "$setup" = gap ]; then
  # the same study without friction: ccx's gap elements have none
  python3 - "$root/comm/sdnv103b.comm" "$work/aster/sdnv103b.comm" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
for key in ("FROTTEMENT", "ALGO_FROT", "E_T", "COULOMB", "COEF_MATR_FROT"):
    text, n = re.subn(r"\n\s*" + key + r"\s*=\s*[^,\n]+,", "", text)
    if n != 1:
        sys.exit(f"calculix.sh: {key} found {n} times in DEFI_CONTACT, expected once")
open(sys.argv[2], "w").write(text)
PY
else
  cp "$root/comm/sdnv103b.comm" "$work/aster/sdnv103b.comm"
fi
t0=$(now)
set +e
# one thread, as ccx (aster's element loops would otherwise use every core)
RAYON_NUM_THREADS=1 "$aster" run "$work/aster/sdnv103b.comm" --unit "20=$mesh" --unit "80=$work/aster/sdnv103b.rmed" \
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
  --ccx-timeout "$timeout_s" \
  --model "$([ "$setup" = gap ] && echo "both frictionless (ccx GAPUNI supports, aster DEFI_CONTACT without FROTTEMENT)" \
             || echo "Coulomb 0.25 (ccx node-to-surface contact, aster discrete contact)")"
[ -n "$keep" ] && echo "files kept in $work" >&2
exit 0
