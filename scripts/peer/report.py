#!/usr/bin/env python3
"""Print the side-by-side table of scripts/peer/calculix.sh: B1 DX and A2 DY
at 80 us, wall time and increments of aster and of ccx, and the time ratio.

aster's values are the VALE_CALC of the TEST_RESU report in the .resu (full
precision); ccx's are the last *NODE PRINT blocks of the .dat for the phi = 0
nodes of B1 and A2 (node sets B1W, A2W of med2ccx.py; B1, A2 with --elements
cax). ccx's time 0 is our INST -1e-5, so 80 us is ccx time 9e-5."""
import argparse
import os
import re

T_END = 8.0e-5
T_SHIFT = 1.0e-5  # ccx time = aster INST + T_SHIFT
REF = {"B1 DX": 3.87, "A2 DY": -13.46}  # Stainier & Ponthot 1994, via the comm file


def aster_values(resu):
    """{'B1 DX': v, 'A2 DY': v} from the TEST_RESU report, None if absent."""
    out = {"B1 DX": None, "A2 DY": None}
    if not os.path.exists(resu):
        return out
    lines = open(resu, errors="replace").read().splitlines()
    for i, line in enumerate(lines):
        f = line.split()
        if len(f) == 5 and f[0] == "RESU" and f[2] == "DEPL":
            key = f"{f[4]} {f[3]}"
            if key not in out:
                continue
            for nxt in lines[i + 1:i + 6]:
                g = nxt.split()
                if len(g) >= 5 and g[0] in ("OK", "NOOK"):
                    out[key] = float(g[4])
                    break
    return out


def ccx_values(d):
    """Last printed time, B1 DX and A2 DY at that time, converged increments,
    cut attempts, whether ccx finished, and its error message if any."""
    dat = os.path.join(d, "sdnv103b.dat")
    last = {}
    tlast = None
    if os.path.exists(dat):
        lines = open(dat, errors="replace").read().splitlines()
        head = re.compile(r"displacements \(vx,vy,vz\) for set (\w+) and time\s+(\S+)")
        for i, line in enumerate(lines):
            m = head.search(line)
            if not m:
                continue
            for nxt in lines[i + 1:i + 4]:
                g = nxt.split()
                if len(g) == 4:
                    t = float(m.group(2))
                    s = m.group(1).rstrip("W")
                    last[s] = (t, float(g[1]), float(g[2]))
                    tlast = t
                    break
    inc, cut = 0, 0
    sta = os.path.join(d, "sdnv103b.sta")
    if os.path.exists(sta):
        for line in open(sta, errors="replace"):
            g = line.split()
            if len(g) == 7 and g[0].isdigit():
                if g[2].isdigit():
                    inc += 1
                else:
                    cut += 1
    log = os.path.join(d, "ccx.log")
    text = open(log, errors="replace").read() if os.path.exists(log) else ""
    finished = "Job finished" in text
    err = None
    m = re.search(r"\*ERROR[^\n]*(\n[^\n]+)?", text)
    if m:
        err = " ".join(m.group(0).split())
    vals = {"B1 DX": None, "A2 DY": None}
    if "B1" in last:
        vals["B1 DX"] = last["B1"][1]
    if "A2" in last:
        vals["A2 DY"] = last["A2"][2]
    return tlast, vals, inc, cut, finished, err


def fmt(v, w=10):
    return f"{v:>{w}.4f}" if v is not None else f"{'-':>{w}}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--aster-resu", required=True)
    ap.add_argument("--aster-rc", type=int, required=True)
    ap.add_argument("--aster-time", nargs=2, type=float, required=True)
    ap.add_argument("--ccx-dir", required=True)
    ap.add_argument("--ccx-rc", type=int, required=True)
    ap.add_argument("--ccx-time", nargs=2, type=float, required=True)
    ap.add_argument("--ccx-timeout", type=float, required=True)
    ap.add_argument("--model", default="", help="one line on the contact model of both")
    a = ap.parse_args()
    ta = a.aster_time[1] - a.aster_time[0]
    tc = a.ccx_time[1] - a.ccx_time[0]
    av = aster_values(a.aster_resu)
    tlast, cv, inc, cut, finished, err = ccx_values(a.ccx_dir)
    reached = (tlast - T_SHIFT) if tlast is not None else None
    ccx_done = finished and reached is not None and abs(reached - T_END) < 1e-9

    print()
    if a.model:
        print(f"contact: {a.model}")
    print(f"{'code':<10}{'B1 DX':>10}{'A2 DY':>10}{'at t (us)':>11}{'wall s':>9}"
          f"{'incr.':>7}{'cuts':>6}  status")
    print(f"{'reference':<10}{fmt(REF['B1 DX'])}{fmt(REF['A2 DY'])}{80.0:>11.3f}")
    print(f"{'aster':<10}{fmt(av['B1 DX'])}{fmt(av['A2 DY'])}{80.0:>11.3f}{ta:>9.2f}"
          f"{163:>7}{'':>6}  exit {a.aster_rc}"
          + (" (TEST_RESU NOOK: its values are those of the study as it is,"
             " with friction on the 5 x 20 mesh)" if a.aster_rc == 1 else ""))
    status = "finished" if ccx_done else (
        "timeout" if a.ccx_rc == 124 else f"stopped (exit {a.ccx_rc})")
    at = f"{reached * 1e6:>11.3f}" if reached is not None else f"{'-':>11}"
    print(f"{'ccx':<10}{fmt(cv['B1 DX'])}{fmt(cv['A2 DY'])}{at}{tc:>9.2f}{inc:>7}{cut:>6}  {status}")
    if err:
        print(f"ccx: {err}")
    if ccx_done:
        print(f"time ratio ccx / aster: {tc / ta:.2f}")
    else:
        print(f"time ratio: none (ccx did not reach 80 us; it ran {tc:.2f} s "
              f"to reach {reached * 1e6 if reached is not None else 0:.3f} us)")


if __name__ == "__main__":
    main()
