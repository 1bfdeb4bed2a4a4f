//! CALC_FONCTION: operations on real functions of one parameter (the
//! computations are in [`crate::post::calc_fonction`]).
//!
//! Why these operations: they are what dynamic studies do with the curves
//! RECU_FONCTION extracts (velocity into displacement, sums of reactions,
//! envelopes of several runs). The spectral, complex and nappe operations
//! are declared so that `aster check` accepts a code_aster file using
//! them, and refused when run.

use super::blocks::*;
use super::defi_fonction::PARAMETERS;
use super::post_args::{function_named, function_of, function_overrides};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::diag::Diagnostic;
use crate::post::calc_fonction as ops;
use crate::post::function::Function;
use crate::study::Study;

/// The operations run here, in the order of the catalogue's UN_PARMI.
const BUILT: &[&str] = &[
    "INTEGRE",
    "DERIVE",
    "COMB",
    "MULT",
    "ABS",
    "PUISSANCE",
    "INVERSE",
    "ENVELOPPE",
];

/// Declared for `aster check`, refused when run.
const NOT_BUILT: &[&str] = &[
    "SPEC_OSCI",
    "FFT",
    "EXTRACTION",
    "ASSE",
    "COMPOSE",
    "CORR_ACCE",
    "FRACTILE",
    "MOYENNE",
    "REGR_POLYNOMIALE",
    "INTERPOL_FFT",
];

fn fonction() -> Keyword {
    concept("FONCTION", &[C::Fonction]).required().kw()
}

fn prol(name: &'static str) -> Keyword {
    text(name)
        .into(&["CONSTANT", "LINEAIRE", "EXCLU"])
        .doc("overrides the extension of the result (default: the operation's)")
        .kw()
}

pub fn def() -> CommandDef {
    let mut ops_list: Vec<&'static str> = BUILT.to_vec();
    ops_list.extend(NOT_BUILT);
    let spec = command(
        "CALC_FONCTION",
        Produces::Concept(C::Fonction),
        vec![
            fact(
                "INTEGRE",
                vec![
                    text("METHODE")
                        .into(&["TRAPEZE", "SIMPSON"])
                        .default(t("TRAPEZE"))
                        .doc("TRAPEZE only (SIMPSON is not built)")
                        .kw(),
                    fonction(),
                    real("COEF")
                        .default(r(0.0))
                        .doc("the constant of integration: the value at the first abscissa")
                        .kw(),
                ],
            )
            .doc("cumulative integral at the same abscissas, excluded on both sides; NOM_RESU ACCE -> VITE -> DEPL")
            .kw(),
            fact(
                "DERIVE",
                vec![
                    text("METHODE")
                        .into(&["DIFF_CENTREE"])
                        .default(t("DIFF_CENTREE"))
                        .kw(),
                    fonction(),
                ],
            )
            .doc("(y[i+1] - y[i-1]) / (x[i+1] - x[i-1]) inside, end segment slopes at the ends; NOM_RESU DEPL -> VITE -> ACCE")
            .kw(),
            fact(
                "COMB",
                vec![
                    fonction(),
                    real("COEF").required().doc("coefficient of this function").kw(),
                ],
            )
            .many()
            .doc("Σ COEF f on the union of the abscissas where all can be evaluated; the first function's parameters")
            .kw(),
            fact("MULT", vec![fonction()])
                .many()
                .doc("product of the functions, same support rule as COMB")
                .kw(),
            block(
                "b_comb",
                or(vec![present("COMB"), present("MULT")]),
                vec![concept("LIST_PARA", &[C::Listr8])
                    .doc("abscissas of the result (the result evaluated there)")
                    .kw()],
            )
            .kw(),
            fact("ABS", vec![fonction()])
                .doc("|y| at the same points (a linear extension becomes excluded)")
                .kw(),
            fact(
                "PUISSANCE",
                vec![
                    fonction(),
                    int("EXPOSANT").default(i(1)).doc("a positive integer").kw(),
                ],
            )
            .doc("y^EXPOSANT at the same points")
            .kw(),
            fact("INVERSE", vec![fonction()])
                .doc("x(y) of a strictly monotonic function; NOM_RESU TOUTRESU")
                .kw(),
            fact(
                "ENVELOPPE",
                vec![
                    concept("FONCTION", &[C::Fonction]).required().many().kw(),
                    text("CRITERE")
                        .into(&["SUP", "INF"])
                        .default(t("SUP"))
                        .doc("upper (max) or lower (min) envelope")
                        .kw(),
                ],
            )
            .doc("pointwise max (or min) on the union of all abscissas; the first function's parameters")
            .kw(),
            fact(
                "SPEC_OSCI",
                vec![
                    text("TYPE_RESU").into(&["NAPPE", "FONCTION"]).kw(),
                    text("METHODE").into(&["NIGAM", "HARMO", "RICE"]).kw(),
                    fonction(),
                    real("AMOR_REDUIT").many().kw(),
                    concept("LIST_FREQ", &[C::Listr8]).kw(),
                    real("FREQ").many().kw(),
                    real("NORME").required().kw(),
                    text("NATURE").into(&["DEPL", "VITE", "ACCE"]).kw(),
                    text("NATURE_FONC").into(&["ACCE", "DSP"]).kw(),
                ],
            )
            .doc("not built")
            .kw(),
            fact(
                "FFT",
                vec![
                    fonction(),
                    text("METHODE").into(&["PROL_ZERO", "TRONCATURE", "COMPLET"]).kw(),
                    text("SYME").into(&["OUI", "NON"]).kw(),
                ],
            )
            .doc("not built")
            .kw(),
            fact(
                "EXTRACTION",
                vec![
                    fonction(),
                    text("PARTIE")
                        .required()
                        .into(&["REEL", "IMAG", "MODULE", "PHASE"])
                        .kw(),
                ],
            )
            .doc("not built (complex functions)")
            .kw(),
            fact(
                "ASSE",
                vec![
                    concept("FONCTION", &[C::Fonction]).required().count(2, 2).kw(),
                    text("SURCHARGE").into(&["DROITE", "GAUCHE"]).kw(),
                ],
            )
            .doc("not built")
            .kw(),
            fact(
                "COMPOSE",
                vec![
                    concept("FONC_RESU", &[C::Fonction]).required().kw(),
                    concept("FONC_PARA", &[C::Fonction]).required().kw(),
                ],
            )
            .doc("not built")
            .kw(),
            fact(
                "CORR_ACCE",
                vec![
                    fonction(),
                    text("METHODE").required().into(&["FILTRAGE", "POLYNOME"]).kw(),
                    real("FREQ_FILTRE").kw(),
                    text("CORR_DEPL").into(&["OUI", "NON"]).kw(),
                ],
            )
            .doc("not built")
            .kw(),
            fact(
                "FRACTILE",
                vec![
                    concept("FONCTION", &[C::Fonction]).required().many().kw(),
                    real("FRACT").kw(),
                ],
            )
            .doc("not built")
            .kw(),
            fact(
                "MOYENNE",
                vec![concept("FONCTION", &[C::Fonction]).required().many().kw()],
            )
            .doc("not built")
            .kw(),
            fact(
                "REGR_POLYNOMIALE",
                vec![fonction(), int("DEGRE").required().kw()],
            )
            .doc("not built")
            .kw(),
            fact(
                "INTERPOL_FFT",
                vec![
                    fonction(),
                    real("PAS_INST").required().kw(),
                    real("PRECISION").kw(),
                ],
            )
            .doc("not built")
            .kw(),
            text("NOM_PARA").into(PARAMETERS).doc("overrides the parameter name").kw(),
            text("NOM_RESU").doc("overrides the value name").kw(),
            text("INTERPOL")
                .count(1, 2)
                .into(&["LIN", "LOG"])
                .doc("overrides the interpolation (default: the operation's, from its first function)")
                .kw(),
            prol("PROL_DROITE"),
            prol("PROL_GAUCHE"),
            info(),
        ],
    )
    .rules(vec![un_parmi(&ops_list)])
    .doc("Computes a function from others: INTEGRE, DERIVE, COMB, MULT, ABS, PUISSANCE, INVERSE, ENVELOPPE.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    if let Some(op) = NOT_BUILT.iter().find(|k| args.has(k)) {
        return Err(args.not_implemented(op, &format!("operations built: {}", BUILT.join(", "))));
    }
    let Some(op) = BUILT.iter().copied().find(|k| args.has(k)) else {
        return Err(args.error("", format!("one of {} is needed", BUILT.join(", "))));
    };
    let occs = args.facts(op);
    let first = occs
        .first()
        .ok_or_else(|| args.error(op, format!("{op} has no occurrence")))?;
    let on = |r: Result<Function, String>, at: &Args| r.map_err(|m| at.error("FONCTION", m));
    let mut f = match op {
        "INTEGRE" => {
            if first.text("METHODE") == Some("SIMPSON") {
                return Err(first.not_implemented("METHODE", "METHODE='SIMPSON'; TRAPEZE is built"));
            }
            let g = function_of(study, first, "FONCTION")?;
            on(
                ops::integrate_trapezoid(g, first.real("COEF").unwrap_or(0.0)),
                first,
            )?
        }
        "DERIVE" => on(ops::derive(function_of(study, first, "FONCTION")?), first)?,
        "ABS" => on(ops::abs(function_of(study, first, "FONCTION")?), first)?,
        "INVERSE" => on(ops::inverse(function_of(study, first, "FONCTION")?), first)?,
        "PUISSANCE" => {
            let g = function_of(study, first, "FONCTION")?;
            ops::power(g, first.int("EXPOSANT").unwrap_or(1))
                .map_err(|m| first.error("EXPOSANT", m))?
        }
        "COMB" => {
            let mut terms = Vec::new();
            for o in occs {
                terms.push((
                    function_of(study, o, "FONCTION")?,
                    o.real("COEF").unwrap_or(0.0),
                ));
            }
            let r = ops::combine(&terms).map_err(|m| args.error("COMB", m))?;
            with_list_para(study, args, r)?
        }
        "MULT" => {
            let mut fs = Vec::new();
            for o in occs {
                fs.push(function_of(study, o, "FONCTION")?);
            }
            let r = ops::multiply(&fs).map_err(|m| args.error("MULT", m))?;
            with_list_para(study, args, r)?
        }
        _ => {
            let mut fs = Vec::new();
            for name in first.concepts("FONCTION") {
                fs.push(function_named(study, first, "FONCTION", name)?);
            }
            let upper = first.text("CRITERE") != Some("INF");
            on(ops::envelope(&fs, upper), first)?
        }
    };
    // Large COEF or EXPOSANT values, or steps near round-off in DERIVE,
    // overflow: refused here rather than stored and tested.
    if let Some(i) = f.ordinates.iter().position(|y| !y.is_finite()) {
        return Err(args.error(
            op,
            format!(
                "the result of {op} is not finite at {}={} (overflow)",
                f.para,
                crate::post::test_report::py_repr(f.abscissas[i])
            ),
        ));
    }
    function_overrides(args, &mut f)?;
    Ok(Some(ConceptData::Function(Box::new(f))))
}

/// The COMB / MULT result evaluated at LIST_PARA, when given.
fn with_list_para(study: &Study, args: &Args, f: Function) -> Result<Function, Diagnostic> {
    let Some(name) = args.concept("LIST_PARA") else {
        return Ok(f);
    };
    let list = match study.concepts.data(name) {
        Some(ConceptData::ListReal(v)) => v.clone(),
        _ => return Err(args.error("LIST_PARA", format!("{name} holds no list of reals"))),
    };
    ops::resample(("the result", &f), &list).map_err(|m| args.error("LIST_PARA", m))
}
