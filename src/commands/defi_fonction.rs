//! DEFI_FONCTION: a real function of one parameter given by points
//! (enough for LIAISON_UNIL's COEF_IMPO and AFFE_CHAR_MECA_F's values of
//! INST or of X, Y, Z, and for any other tabulated function of the
//! studies).

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::post::function::{Extrapolation, Function, Interp};
use crate::study::Study;

/// The parameters a function may have (code_aster's C_PARA_FONCTION, the
/// part the studies use).
pub const PARAMETERS: &[&str] = &[
    "INST", "X", "Y", "Z", "ABSC", "FREQ", "TEMP", "EPSI", "SIGM", "DX", "DY", "DZ",
];

pub fn def() -> CommandDef {
    let prol = |name: &'static str| {
        text(name)
            .into(&["CONSTANT", "LINEAIRE", "EXCLU"])
            .default(t("EXCLU"))
            .doc("extension beyond the abscissas")
            .kw()
    };
    let spec = command(
        "DEFI_FONCTION",
        Produces::Concept(C::Fonction),
        vec![
            text("NOM_PARA")
                .required()
                .into(PARAMETERS)
                .doc("the parameter (INST, X, Y, Z...)")
                .kw(),
            text("NOM_RESU").default(t("TOUTRESU")).kw(),
            real("VALE")
                .many()
                .doc("x1, y1, x2, y2, ... (abscissas increasing)")
                .kw(),
            real("VALE_C").many().hidden().kw(),
            real("ABSCISSE").many().kw(),
            real("ORDONNEE").many().kw(),
            real("VALE_PARA").many().kw(),
            real("VALE_FONC").many().kw(),
            text("NOEUD_PARA").many().hidden().kw(),
            text("INTERPOL")
                .into(&["NON", "LIN", "LOG", "INT"])
                .count(1, 2)
                .default(t("LIN"))
                .doc("interpolation on the abscissa (and the ordinate)")
                .kw(),
            prol("PROL_GAUCHE"),
            prol("PROL_DROITE"),
            text("VERIF")
                .into(&["CROISSANT", "NON"])
                .default(t("CROISSANT"))
                .kw(),
            info(),
            titre(),
        ],
    )
    .rules(vec![
        un_parmi(&["VALE", "VALE_C", "ABSCISSE", "VALE_PARA", "NOEUD_PARA"]),
        Rule::Together(vec!["ABSCISSE", "ORDONNEE"]),
        Rule::Together(vec!["VALE_PARA", "VALE_FONC"]),
    ])
    .doc("Defines a real function of one parameter by its points, LIN or LOG interpolation.");
    CommandDef { spec, exec }
}

fn interp(args: &Args, name: &str) -> Result<Interp, crate::diag::Diagnostic> {
    match name {
        "LIN" => Ok(Interp::Lin),
        "LOG" => Ok(Interp::Log),
        other => Err(args.not_implemented("INTERPOL", &format!("INTERPOL='{other}'"))),
    }
}

fn exec(_study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    for key in ["VALE_C", "NOEUD_PARA"] {
        if args.given(key) {
            return Err(args.not_implemented(key, "only real functions given by their points"));
        }
    }
    let (key, xs, ys) = if args.has("VALE") {
        let v = args.reals("VALE");
        if !v.len().is_multiple_of(2) {
            return Err(args.error(
                "VALE",
                format!(
                    "VALE holds {} values: an even count (x1, y1, x2, y2, ...) is expected",
                    v.len()
                ),
            ));
        }
        let xs = v.iter().step_by(2).copied().collect::<Vec<_>>();
        let ys = v.iter().skip(1).step_by(2).copied().collect::<Vec<_>>();
        ("VALE", xs, ys)
    } else if args.has("ABSCISSE") {
        ("ABSCISSE", args.reals("ABSCISSE"), args.reals("ORDONNEE"))
    } else {
        (
            "VALE_PARA",
            args.reals("VALE_PARA"),
            args.reals("VALE_FONC"),
        )
    };
    let mut pairs: Vec<(f64, f64)> = xs.into_iter().zip(ys.iter().copied()).collect();
    if args.text("VERIF") == Some("NON") {
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    let para = args.text("NOM_PARA").unwrap_or("INST");
    let resu = args.text("NOM_RESU").unwrap_or("TOUTRESU");
    let (xs, ys2): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
    if xs.len() != ys.len() {
        return Err(args.error(
            key,
            format!(
                "{} abscissas and {} ordinates: they must be as many",
                xs.len(),
                ys.len()
            ),
        ));
    }
    let mut f = Function::new(para, resu, xs, ys2).map_err(|m| args.error(key, m))?;
    let inter = args.texts("INTERPOL");
    let on_x = interp(args, inter.first().copied().unwrap_or("LIN"))?;
    let on_y = interp(
        args,
        inter
            .get(1)
            .copied()
            .unwrap_or(inter.first().copied().unwrap_or("LIN")),
    )?;
    f.interpolation = (on_x, on_y);
    let prol = |k: &str| Extrapolation::parse(args.text(k).unwrap_or("EXCLU")).unwrap_or_default();
    f.left = prol("PROL_GAUCHE");
    f.right = prol("PROL_DROITE");
    Ok(Some(ConceptData::Function(Box::new(f))))
}
