//! Contact in explicit dynamics (an aster extension) on the landing bar of
//! tests/verification/explicit_landing.comm, beyond its TEST_TABLE: every
//! row of the energy balance, and the momentum exchanged with the rigid
//! foundation against the impulse of the contact reactions (two sums the
//! engine computes independently: Σ M v over the model, and the
//! trapezoidal time integral of the contact forces), and the rebound.

mod common;

/// The numbers in parentheses after `tag` on each line of `mess` that has it.
fn tuples(mess: &str, tag: &str) -> Vec<Vec<f64>> {
    mess.lines()
        .filter_map(|l| l.find(tag).map(|k| &l[k + tag.len()..]))
        .map(|rest| {
            let a = rest.find('(').unwrap();
            let b = rest.find(')').unwrap();
            rest[a + 1..b]
                .split(',')
                .map(|x| x.trim().parse::<f64>().unwrap())
                .collect()
        })
        .collect()
}

#[test]
fn landing_bar_momentum_is_the_impulse_of_the_reactions() {
    let run = common::run_study(
        "tests/verification/explicit_landing.comm",
        "explicit_landing",
    );
    let resu = common::assert_all_ok(&run, "explicit_landing.resu");
    let mess = run.file("explicit_landing.mess");
    let impulse = tuples(&mess, "impulse of the contact reactions on the bodies ");
    let momentum = tuples(&mess, "momentum of the model (M v): change over the run ");
    assert_eq!(impulse.len(), 2, "{mess}");
    assert_eq!(momentum.len(), 2);
    // p0 = rho R^2/2 L |V0| per radian.
    let p0 = 8.93e-9 * 3.2 * 3.2 / 2.0 * 32.4 * 1.0e4;
    for (k, (i, m)) in impulse.iter().zip(&momentum).enumerate() {
        assert!(
            (i[1] - m[1]).abs() <= 1e-9 * i[1].abs(),
            "run {k}: impulse {} against momentum change {}",
            i[1],
            m[1]
        );
        // The bar leaves the foundation: the momentum is reversed, less the
        // kinematic impact's loss (notes/explicit.md §10.1) or the penalty's
        // residual vibration.
        let ratio = i[1] / p0;
        assert!(
            (1.85..=2.0).contains(&ratio),
            "run {k}: impulse / p0 = {ratio}"
        );
    }
    // Every row of both balances: |DISS_SCH| < 1 % of EK0.
    let ek0 = 74.068992;
    let mut rows = 0;
    for l in resu.lines() {
        let t: Vec<&str> = l.split_whitespace().collect();
        if t.len() == 9 && t[0].parse::<usize>().is_ok() {
            let diss: f64 = t[8].parse().unwrap();
            assert!(diss.abs() < 0.01 * ek0, "{l}");
            rows += 1;
        }
    }
    assert!(rows >= 60, "{rows} rows");
}

/// A stiff penalty (E_N = 1e9 on the landing bar) lowers the stable step by
/// more than 10 times: the .mess reports the factor and an alarm gives the
/// step it implies; the CFL message names the penalty as the limit.
#[test]
fn stiff_penalty_step_is_reported_with_an_alarm() {
    let run = common::run_study(
        "tests/verification/explicit_penalty_step.comm",
        "explicit_penalty_step",
    );
    common::assert_all_ok(&run, "explicit_penalty_step.resu");
    let mess = run.file("explicit_penalty_step.mess");
    let alarm = mess
        .lines()
        .find(|l| {
            l.contains("alarm: the contact penalty shrinks the stable step by more than 10 times")
        })
        .unwrap_or_else(|| panic!("no alarm in:\n{mess}"));
    // "... times: A s instead of B s (...)": A = B / factor, factor > 10.
    let after = &alarm[alarm.find("times:").unwrap()..];
    let nums: Vec<f64> = after
        .split_whitespace()
        .filter_map(|w| w.parse::<f64>().ok())
        .collect();
    assert!(nums.len() >= 2 && nums[0] < nums[1] / 10.0, "{alarm}");
    assert!(
        mess.contains("set by the contact penalty") && mess.contains("STOP_CFL='NON'"),
        "{mess}"
    );
}
