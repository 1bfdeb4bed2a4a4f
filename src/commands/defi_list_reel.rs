//! DEFI_LIST_REEL: an increasing list of reals (time lists).

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::diag::Diagnostic;
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_LIST_REEL",
        Produces::Concept(C::Listr8),
        vec![
            real("VALE").many().doc("explicit, strictly increasing values").kw(),
            real("DEBUT").doc("first value of a list built by intervals").kw(),
            fact(
                "INTERVALLE",
                vec![
                    real("JUSQU_A")
                        .required()
                        .doc("end of the interval, reached exactly")
                        .kw(),
                    int("NOMBRE")
                        .doc("number of equal sub-intervals (new values)")
                        .kw(),
                    real("PAS")
                        .doc("step; a shorter last step is added, with an alarm, when it does not divide the interval")
                        .kw(),
                ],
            )
            .many()
            .rules(vec![un_parmi(&["NOMBRE", "PAS"])])
            .doc("intervals following each other from DEBUT")
            .kw(),
            info(),
            titre(),
        ],
    )
    .rules(vec![
        un_parmi(&["VALE", "DEBUT"]),
        exclus(&["VALE", "INTERVALLE"]),
        ensemble(&["DEBUT", "INTERVALLE"]),
    ])
    .doc("Defines a strictly increasing list of reals, explicitly or by intervals.");
    CommandDef { spec, exec }
}

/// code_aster's tolerance on the number of PAS steps in an interval.
const PAS_TOLERANCE: f64 = 1e-3;

/// The most values a list may hold (80 MB of reals). code_aster has no
/// such limit, but a mistyped NOMBRE or PAS (1e12 steps) would otherwise
/// fill the memory before anything is reported; no transient study of
/// this size range needs more.
pub const MAX_VALUES: usize = 10_000_000;

fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let values = if args.has("VALE") {
        explicit(args)?
    } else {
        let debut = args
            .real("DEBUT")
            .ok_or_else(|| args.error("DEBUT", "DEBUT or VALE is required"))?;
        let mut alarms = Vec::new();
        let v = by_intervals(debut, args.facts("INTERVALLE"), &mut alarms)?;
        for a in alarms {
            study.log(a);
        }
        v
    };
    Ok(Some(ConceptData::ListReal(values)))
}

fn explicit(args: &Args) -> Result<Vec<f64>, Diagnostic> {
    strictly_increasing(args, args.reals("VALE"), |x| format!("{x:e}"))
}

/// VALE of a list command, refused unless strictly increasing (the error
/// names the first value out of order, written by `show`).
pub(super) fn strictly_increasing<T: PartialOrd + Copy>(
    args: &Args,
    v: Vec<T>,
    show: impl Fn(T) -> String,
) -> Result<Vec<T>, Diagnostic> {
    if let Some(k) = (1..v.len()).find(|&k| v[k] <= v[k - 1]) {
        return Err(args.error(
            "VALE",
            format!(
                "the values must be strictly increasing: value {} ({}) follows {}",
                k + 1,
                show(v[k]),
                show(v[k - 1])
            ),
        ));
    }
    Ok(v)
}

/// Builds the list from DEBUT and the INTERVALLE occurrences as code_aster
/// does (op0024): values are accumulated step by step, which is why an
/// accumulated value within machine epsilon of zero is snapped to exactly
/// 0.0 (so that a list through t = 0 contains 0.0), and each interval ends
/// exactly on its JUSQU_A whatever the rounding. Alarms are returned as
/// message lines.
pub fn by_intervals(
    debut: f64,
    intervals: &[Args],
    alarms: &mut Vec<String>,
) -> Result<Vec<f64>, Diagnostic> {
    let mut values = vec![debut];
    let mut prev = debut;
    for occ in intervals {
        let end = occ
            .real("JUSQU_A")
            .ok_or_else(|| occ.error("JUSQU_A", "JUSQU_A is required"))?;
        if end <= prev {
            return Err(occ.error(
                "JUSQU_A",
                format!("JUSQU_A = {end:e} must be greater than the previous value {prev:e}"),
            ));
        }
        let length = end - prev;
        let (steps, step) = if let Some(n) = occ.int("NOMBRE") {
            if n < 1 {
                return Err(occ.error("NOMBRE", format!("NOMBRE = {n} must be at least 1")));
            }
            if n as u64 > MAX_VALUES as u64 {
                return Err(occ.error(
                    "NOMBRE",
                    format!("NOMBRE = {n} is more than the {MAX_VALUES} values a list may hold"),
                ));
            }
            (n as usize, length / n as f64)
        } else {
            let pas = occ
                .real("PAS")
                .ok_or_else(|| occ.error("", "one of NOMBRE or PAS is required"))?;
            if pas <= 0.0 {
                return Err(occ.error("PAS", format!("PAS = {pas:e} must be positive")));
            }
            let ratio = length / pas;
            if ratio > MAX_VALUES as f64 {
                return Err(occ.error(
                    "PAS",
                    format!(
                        "PAS = {pas:e} cuts [{prev:e}, {end:e}] into {ratio:e} steps, more than the {MAX_VALUES} values a list may hold"
                    ),
                ));
            }
            if ratio <= 1.0 - PAS_TOLERANCE {
                return Err(occ.error(
                    "PAS",
                    format!("PAS = {pas:e} is longer than the interval [{prev:e}, {end:e}]"),
                ));
            }
            let whole = ratio.round();
            if (ratio - whole).abs() <= PAS_TOLERANCE {
                (whole as usize, pas)
            } else {
                // Full steps of PAS, then a shorter last step to JUSQU_A.
                let full = ratio.floor() as usize;
                alarms.push(format!(
                    "<A> DEFI_LIST_REEL: PAS = {pas:e} does not divide [{prev:e}, {end:e}] \
                     ({ratio} steps); the last step is shortened to reach JUSQU_A = {end:e}"
                ));
                (full + 1, pas)
            }
        };
        if values.len() + steps > MAX_VALUES {
            return Err(occ.error(
                "",
                format!("the intervals give more than the {MAX_VALUES} values a list may hold"),
            ));
        }
        // A step below the spacing of reals near the interval would give
        // a list that does not increase.
        if prev + step <= prev || end - step >= end {
            return Err(occ.error(
                if occ.has("NOMBRE") { "NOMBRE" } else { "PAS" },
                format!(
                    "the step {step:e} is below the resolution of reals in [{prev:e}, {end:e}]"
                ),
            ));
        }
        let mut v = prev;
        for k in 1..steps {
            v += step;
            if v.abs() <= f64::EPSILON {
                v = 0.0;
                // code_aster's snap to 0 (op0024: |v| <= r8prem) undoes a
                // step this small: the next value lands on 0 again and the
                // list stops increasing.
                if values.last().is_some_and(|&last| v <= last) {
                    return Err(occ.error(
                        if occ.has("NOMBRE") { "NOMBRE" } else { "PAS" },
                        format!(
                            "the step {step:e} from {prev:e} is not above the machine precision {:e}: \
                             code_aster's DEFI_LIST_REEL sets every accumulated value within {:e} of 0 \
                             to exactly 0 (so that a list through t = 0 holds 0), so the value after \
                             {k} step(s) of this interval would be 0 again and the list would not \
                             increase; give such instants with VALE=(...), which keeps them as written",
                            f64::EPSILON,
                            f64::EPSILON,
                        ),
                    ));
                }
            }
            values.push(v);
        }
        values.push(end);
        prev = end;
    }
    Ok(values)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog::args::{Entry, EntryData, Value};
    use crate::diag::Span;

    fn level(keys: &[(&str, Value)]) -> Args {
        let mut a = Args::new("DEFI_LIST_REEL", "INTERVALLE", Span::new(0, 0));
        for (k, v) in keys {
            a.entries.insert(
                k.to_string(),
                Entry {
                    span: Span::new(0, 0),
                    defaulted: false,
                    data: EntryData::Simple(vec![v.clone()]),
                },
            );
        }
        a
    }
    fn nombre(end: f64, n: i64) -> Args {
        level(&[("JUSQU_A", Value::Real(end)), ("NOMBRE", Value::Int(n))])
    }
    fn pas(end: f64, p: f64) -> Args {
        level(&[("JUSQU_A", Value::Real(end)), ("PAS", Value::Real(p))])
    }
    fn build(debut: f64, iv: &[Args]) -> (Vec<f64>, Vec<String>) {
        let mut alarms = Vec::new();
        let v = by_intervals(debut, iv, &mut alarms).expect("valid list");
        (v, alarms)
    }

    /// sdnv103b's L_INST: 1 + 1 + 4 + 158 values, ends exact, steps as
    /// computed by hand from the interval lengths.
    #[test]
    fn sdnv103b_list() {
        let (v, alarms) = build(
            -1e-5,
            &[nombre(-1e-7, 1), nombre(1e-6, 4), nombre(8e-5, 158)],
        );
        assert!(alarms.is_empty());
        assert_eq!(v.len(), 164);
        assert_eq!(v[0], -1e-5);
        assert_eq!(v[1], -1e-7);
        assert_eq!(v[5], 1e-6);
        assert_eq!(*v.last().unwrap(), 8e-5);
        // Interior steps of the last interval: (8e-5 - 1e-6)/158 = 5e-7,
        // to within accumulated rounding (1e-12 relative is far above it).
        for w in v[5..].windows(2) {
            assert!(((w[1] - w[0]) - 5e-7).abs() < 1e-12 * 5e-7 * 158.0);
        }
        // The second interval: steps of 2.75e-7 from -1e-7.
        assert!((v[2] - 1.75e-7).abs() < 1e-20);
    }

    /// sdnv103a's L_INST passes through exactly 0.0 at -2.5e-7 + 5 * 5e-8.
    #[test]
    fn sdnv103a_list_contains_exact_zero() {
        let (v, _) = build(
            -1e-5,
            &[nombre(-2.5e-7, 1), nombre(2.5e-7, 10), nombre(8e-5, 316)],
        );
        assert_eq!(v.len(), 1 + 1 + 10 + 316);
        assert_eq!(v[6], 0.0);
        assert_eq!(v[11], 2.5e-7);
        assert_eq!(*v.last().unwrap(), 8e-5);
        assert!(v.windows(2).all(|w| w[1] > w[0]));
    }

    #[test]
    fn pas_dividing_the_interval() {
        let (v, alarms) = build(0.0, &[pas(1.0, 0.25)]);
        assert_eq!(v, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
        assert!(alarms.is_empty());
    }

    /// 1.0 / 0.3 = 3.33 steps: three steps of 0.3 then 0.1, with an alarm.
    #[test]
    fn pas_with_short_last_step() {
        let (v, alarms) = build(0.0, &[pas(1.0, 0.3)]);
        assert_eq!(v.len(), 5);
        assert!((v[3] - 0.9).abs() < 1e-15);
        assert_eq!(v[4], 1.0);
        assert_eq!(alarms.len(), 1);
    }

    /// Within the 1e-3 tolerance the step count is rounded, no alarm.
    #[test]
    fn pas_within_tolerance() {
        let (v, alarms) = build(0.0, &[pas(1.0, 0.20001)]);
        assert_eq!(v.len(), 6);
        assert_eq!(v[5], 1.0);
        assert!(alarms.is_empty());
    }

    #[test]
    fn pas_longer_than_interval_is_fatal() {
        let mut alarms = Vec::new();
        let e = by_intervals(0.0, &[pas(1.0, 2.0)], &mut alarms).unwrap_err();
        assert!(
            e.message.contains("longer than the interval"),
            "{}",
            e.message
        );
        assert_eq!(e.keyword.as_deref(), Some("INTERVALLE/PAS"));
    }

    /// Found by tests/fuzz_runner.rs: NOMBRE = i64::MAX filled the memory.
    #[test]
    fn too_many_values_is_fatal_before_any_allocation() {
        let mut alarms = Vec::new();
        let e = by_intervals(0.0, &[nombre(1.0, i64::MAX)], &mut alarms).unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("INTERVALLE/NOMBRE"));
        let e = by_intervals(0.0, &[pas(1.0, 1e-300)], &mut alarms).unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("INTERVALLE/PAS"));
        let half = nombre(1.0, (MAX_VALUES / 2 + 1) as i64);
        let e = by_intervals(
            0.0,
            &[half, nombre(2.0, (MAX_VALUES / 2) as i64)],
            &mut alarms,
        )
        .unwrap_err();
        assert!(e.message.contains("more than"), "{}", e.message);
    }

    /// A step below the spacing of reals would repeat a value.
    #[test]
    fn step_below_the_resolution_of_reals_is_fatal() {
        let mut alarms = Vec::new();
        let e = by_intervals(1e10, &[nombre(1e10 + 1e-4, 1000)], &mut alarms).unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("INTERVALLE/NOMBRE"));
        assert!(e.message.contains("resolution"), "{}", e.message);
    }

    #[test]
    fn decreasing_interval_is_fatal() {
        let mut alarms = Vec::new();
        let e = by_intervals(1.0, &[nombre(0.5, 2)], &mut alarms).unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("INTERVALLE/JUSQU_A"));
    }

    #[test]
    fn explicit_values_must_increase() {
        let mut a = Args::new("DEFI_LIST_REEL", "", Span::new(0, 0));
        a.entries.insert(
            "VALE".into(),
            Entry {
                span: Span::new(0, 0),
                defaulted: false,
                data: EntryData::Simple(vec![Value::Real(0.0), Value::Int(1), Value::Real(0.5)]),
            },
        );
        let e = explicit(&a).unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("VALE"));
        a.entries.get_mut("VALE").unwrap().data =
            EntryData::Simple(vec![Value::Real(0.0), Value::Int(1), Value::Real(1.5)]);
        assert_eq!(explicit(&a).unwrap(), vec![0.0, 1.0, 1.5]);
    }
}
