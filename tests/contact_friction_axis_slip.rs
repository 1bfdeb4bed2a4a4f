//! The Newton cycle of discrete penalised contact with Coulomb friction
//! (probe h20_axis_slip_newton_cycle: a HEXA20 block sliding along a
//! tangent of its QUAD8 face, period-3 open/contact cycle of whole node
//! rows): `nonlinear::contact::newton_cycle` recognises a repeated
//! iterate and names the switching slave nodes, so the step fails at once
//! (DECOUPE cuts it) instead of after ITER_GLOB_MAXI; it never fires on a
//! converging sequence.

use aster::contact::LinkStatus::{self, Open, Slip, Stick};
use aster::nonlinear::contact::newton_cycle;

type Iterate = (f64, Vec<(usize, LinkStatus)>);

fn it(resi: f64, statuses: &[LinkStatus]) -> Iterate {
    (
        resi,
        statuses
            .iter()
            .copied()
            .enumerate()
            .map(|(i, s)| (8 + i, s))
            .collect(),
    )
}

/// The probe's period: rows open and close with RESI 0.97, 0.94, 0.146.
fn period() -> Vec<Iterate> {
    vec![
        it(0.9721, &[Open, Open, Slip, Slip]),
        it(0.9448, &[Open, Open, Open, Slip]),
        it(0.1458, &[Slip, Slip, Slip, Open]),
    ]
}

#[test]
fn a_period_three_contact_cycle_is_named_after_three_periods() {
    let mut h: Vec<Iterate> = vec![it(f64::INFINITY, &[Slip; 4]), it(0.5, &[Slip; 4])];
    for _ in 0..2 {
        h.extend(period());
    }
    assert!(newton_cycle(&h).is_none(), "two periods are not enough");
    h.extend(period());
    let m = newton_cycle(&h).expect("three periods: a cycle");
    assert!(m.contains("period 3"), "{m}");
    assert!(m.contains("between contact and open"), "{m}");
    // Slave nodes 8..11 are N9..N12; every one of them switches.
    for n in [
        "N9 (0 -> 0 -> 2)",
        "N10",
        "N11 (2 -> 0 -> 2)",
        "N12 (2 -> 2 -> 0)",
    ] {
        assert!(m.contains(n), "{n} missing: {m}");
    }
    assert!(m.contains("DECOUPE"), "{m}");
}

#[test]
fn a_stick_slip_two_cycle_is_named() {
    let mut h = Vec::new();
    for _ in 0..3 {
        h.push(it(1.0, &[Open, Slip]));
        h.push(it(2.4404e-3, &[Stick, Slip]));
    }
    let m = newton_cycle(&h).expect("a cycle");
    assert!(
        m.contains("period 2") && m.contains("1 slave node(s)"),
        "{m}"
    );
    assert!(m.contains("N9 (0 -> 1)"), "{m}");
}

#[test]
fn converging_or_static_sequences_are_not_cycles() {
    // Same statuses, decreasing residual: Newton converging.
    let h: Vec<Iterate> = (0..12)
        .map(|k| it(0.5f64.powi(k), &[Slip, Slip, Open]))
        .collect();
    assert!(newton_cycle(&h).is_none());
    // Statuses cycling but residuals still moving (beyond 1e-6).
    let mut h = Vec::new();
    for k in 0..4 {
        let f = 1.0 - 1e-3 * k as f64;
        h.push(it(0.9 * f, &[Open, Slip]));
        h.push(it(0.1 * f, &[Slip, Slip]));
    }
    assert!(newton_cycle(&h).is_none());
    // A repeated residual with no status switching is not a contact cycle.
    let h: Vec<Iterate> = (0..12)
        .map(|k| it(if k % 2 == 0 { 0.3 } else { 0.2 }, &[Slip, Slip]))
        .collect();
    assert!(newton_cycle(&h).is_none());
    // The prediction's RESI is +inf: never equal to anything.
    let h: Vec<Iterate> = (0..9).map(|_| it(f64::INFINITY, &[Open, Slip])).collect();
    assert!(newton_cycle(&h).is_none());
}
