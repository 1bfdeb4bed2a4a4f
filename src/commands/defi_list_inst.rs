//! DEFI_LIST_INST: a time list with step-cutting and adaptation rules.

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::study::Study;
use crate::time::list::{
    Action, AdaptEvent, Adaptation, Event, FailureRule, Subdivision, TimeList, TplusMode,
};

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_LIST_INST",
        Produces::Concept(C::ListInst),
        vec![
            text("METHODE")
                .into(&["MANUEL", "AUTO"])
                .default(t("MANUEL"))
                .doc("fixed list, or steps that grow on success (AUTO)")
                .kw(),
            block(
                "b_manuel",
                eq("METHODE", "MANUEL"),
                vec![fact(
                    "DEFI_LIST",
                    vec![
                        real("VALE").many().kw(),
                        concept("LIST_INST", &[C::Listr8]).kw(),
                        concept("RESULTAT", &[C::EvolNoli])
                            .doc("take the instants of a result")
                            .kw(),
                        int("SUBD_PAS")
                            .min_val(1.0)
                            .doc("split each step of RESULTAT")
                            .kw(),
                    ],
                )
                .required()
                .rules(vec![
                    un_parmi(&["LIST_INST", "VALE", "RESULTAT"]),
                    present_present("RESULTAT", &["SUBD_PAS"]),
                ])
                .doc("the instants")
                .kw()],
            )
            .kw(),
            block(
                "b_auto",
                eq("METHODE", "AUTO"),
                vec![
                    fact(
                        "DEFI_LIST",
                        vec![
                            real("VALE").many().kw(),
                            concept("LIST_INST", &[C::Listr8]).kw(),
                            real("PAS_MINI").min_val(1e-12).doc("smallest step").kw(),
                            real("PAS_MAXI").doc("largest step").kw(),
                            int("NB_PAS_MAXI")
                                .default(i(1000000))
                                .max_val(1e6)
                                .kw(),
                        ],
                    )
                    .required()
                    .rules(vec![un_parmi(&["LIST_INST", "VALE"])])
                    .doc("the initial instants")
                    .kw(),
                    adaptation(),
                ],
            )
            .kw(),
            echec(),
            info(),
        ],
    )
    .doc("Defines a time list for INCREMENT/LIST_INST with failure handling (step cutting) and adaptation.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let auto = args.text("METHODE") == Some("AUTO");
    let Some(dl) = args.fact("DEFI_LIST") else {
        return Err(args.error("DEFI_LIST", "DEFI_LIST is required"));
    };
    let instants = instants(study, dl)?;
    let nb_pas_maxi = dl.int("NB_PAS_MAXI").unwrap_or(1_000_000);
    if nb_pas_maxi < 1 {
        return Err(dl.error("NB_PAS_MAXI", "NB_PAS_MAXI must be at least 1"));
    }
    let pas_mini = dl.real("PAS_MINI");
    let pas_maxi = dl.real("PAS_MAXI");
    if let Some(hi) = pas_maxi.filter(|&hi| !(hi > 0.0 && hi.is_finite())) {
        // A step that cannot be positive would never reach the next instant.
        return Err(dl.error(
            "PAS_MAXI",
            format!("PAS_MAXI = {hi:e} must be a positive finite step"),
        ));
    }
    if let (Some(lo), Some(hi)) = (pas_mini, pas_maxi) {
        if lo > hi {
            return Err(dl.error(
                "PAS_MINI",
                format!("PAS_MINI = {lo:e} is larger than PAS_MAXI = {hi:e}"),
            ));
        }
    }
    let mut list = TimeList {
        instants,
        auto,
        pas_mini,
        pas_maxi,
        nb_pas_maxi: nb_pas_maxi as usize,
        rules: Vec::new(),
        adaptation: Vec::new(),
    };
    let min_step = list.min_step().unwrap_or(f64::INFINITY);

    // A defaulted ECHEC is the checker's single default occurrence: it
    // stands for "no rule given", which code_aster turns into the implicit
    // ERREUR rule (with SUBD_PAS_MINI 1e-12, not the catalogue's 0).
    let given_echec = args.given("ECHEC");
    let occs: &[Args] = if given_echec {
        args.facts("ECHEC")
    } else {
        &[]
    };
    let mut seen: Vec<(String, usize)> = Vec::new();
    for (k, occ) in occs.iter().enumerate() {
        let rule = failure_rule(occ)?;
        let name = rule.event.name().to_string();
        if name != "DELTA_GRANDEUR" {
            if let Some((_, first)) = seen.iter().find(|(n, _)| *n == name) {
                return Err(occ.error(
                    "EVENEMENT",
                    format!(
                        "the event {name} is given twice (occurrences {} and {} of ECHEC): give one rule per event",
                        first + 1,
                        k + 1
                    ),
                ));
            }
            seen.push((name, k));
        }
        if let Some(m) = rule.action_subd_pas_mini().filter(|&m| m > min_step) {
            return Err(occ.error(
                "SUBD_PAS_MINI",
                format!(
                    "SUBD_PAS_MINI = {m:e} is larger than the smallest step of the list, {min_step:e} (DISCRETISATION_6)"
                ),
            ));
        }
        list.rules.push(rule);
    }
    let implicit = !list.rules.iter().any(|r| r.event == Event::Erreur);
    if implicit {
        let rule = TimeList::implicit_error_rule();
        if let Some(m) = rule.action_subd_pas_mini().filter(|&m| m > min_step) {
            return Err(args.error(
                "DEFI_LIST",
                format!(
                    "the smallest step of the list, {min_step:e}, is below the SUBD_PAS_MINI = {m:e} of the implicit ERREUR rule (DISCRETISATION_6)"
                ),
            ));
        }
        list.rules.push(rule);
    }
    if auto {
        for occ in args.facts("ADAPTATION") {
            list.adaptation.push(adaptation_rule(occ)?);
        }
    }

    let n = list.instants.len();
    study.log(format!(
        "    time list {} (METHODE='{}'): {n} instants from {:e} to {:e}, smallest step {min_step:e}",
        result.unwrap_or("(unnamed)"),
        if auto { "AUTO" } else { "MANUEL" },
        list.instants[0],
        list.instants[n - 1],
    ));
    for (k, r) in list.rules.iter().enumerate() {
        let tag = if implicit && k + 1 == list.rules.len() {
            " (implicit: no ERREUR rule given)"
        } else {
            ""
        };
        study.log(format!("      {} -> {}{tag}", r.event.name(), r.action));
    }
    if let Some(level) = list.max_subd_niveau() {
        study.log(format!(
            "      maximum subdivision level shared by all events: {level}"
        ));
    }
    Ok(Some(ConceptData::TimeList(Box::new(list))))
}

/// The instants of DEFI_LIST: a DEFI_LIST_REEL list, or VALE.
fn instants(study: &Study, dl: &Args) -> Result<Vec<f64>, Diagnostic> {
    let (v, key) = if dl.has("RESULTAT") {
        return Err(dl.not_implemented("RESULTAT", "the instants of a result"));
    } else if let Some(name) = dl.concept("LIST_INST") {
        match study.concepts.data(name) {
            Some(ConceptData::ListReal(v)) => (v.clone(), "LIST_INST"),
            _ => {
                return Err(dl.error(
                    "LIST_INST",
                    format!("the list {name} holds no data (its command did not run)"),
                ))
            }
        }
    } else {
        (dl.reals("VALE"), "VALE")
    };
    if v.len() < 2 {
        return Err(dl.error(
            key,
            format!("a time list needs at least two instants, {} given", v.len()),
        ));
    }
    if let Some(k) = (1..v.len()).find(|&k| v[k] <= v[k - 1]) {
        return Err(dl.error(
            key,
            format!(
                "the instants must be strictly increasing: instant {} ({:e}) follows {:e}",
                k + 1,
                v[k],
                v[k - 1]
            ),
        ));
    }
    Ok(v)
}

/// One ECHEC occurrence. Values the catalogue always fills are read with
/// code_aster's defaults as a fallback only.
fn failure_rule(occ: &Args) -> Result<FailureRule, Diagnostic> {
    let real = |k: &str| {
        occ.real(k)
            .ok_or_else(|| occ.error(k, format!("{k} is required")))
    };
    let text = |k: &str| occ.text(k).unwrap_or_default().to_string();
    let event = match occ.text("EVENEMENT").unwrap_or("ERREUR") {
        "ERREUR" => Event::Erreur,
        "COLLISION" => Event::Collision,
        "INTERPENETRATION" => Event::Interpenetration {
            pene_maxi: real("PENE_MAXI")?,
        },
        "DELTA_GRANDEUR" => Event::DeltaGrandeur {
            vale_ref: real("VALE_REF")?,
            nom_cham: text("NOM_CHAM"),
            nom_cmp: text("NOM_CMP"),
        },
        "RESI_MAXI" => Event::ResiMaxi {
            resi_glob_maxi: real("RESI_GLOB_MAXI")?,
        },
        other => Event::Other(other.to_string()),
    };
    let action = match occ.text("ACTION").unwrap_or("DECOUPE") {
        "ARRET" => Action::Arret,
        "DECOUPE" => Action::Decoupe(subdivision(occ, &event)?),
        "ITER_SUPPL" => Action::IterSuppl {
            pcent_iter_plus: occ.int("PCENT_ITER_PLUS").unwrap_or(50) as f64,
            subdivision: subdivision(occ, &event)?,
        },
        "ADAPT_COEF_PENA" => Action::AdaptCoefPena {
            coef_maxi: occ.real("COEF_MAXI").unwrap_or(1e12),
        },
        "CONTINUE" => Action::Continue,
        other => {
            return Err(
                occ.not_implemented("ACTION", &format!("ACTION='{other}' (it needs PILOTAGE)"))
            )
        }
    };
    Ok(FailureRule { event, action })
}

/// The cutting method of an occurrence: MANUEL (equal sub-steps, levels),
/// AUTO (collision refinement for COLLISION, extrapolation otherwise).
fn subdivision(occ: &Args, event: &Event) -> Result<Subdivision, Diagnostic> {
    let int = |k: &str, d: i64| occ.int(k).unwrap_or(d);
    let pas_mini = occ.real("SUBD_PAS_MINI").unwrap_or(0.0);
    // SUBD_METHODE defaults to 'AUTO' for COLLISION and 'MANUEL' otherwise
    // (semantics.md 7.2), whatever default the catalogue filled in.
    let default = if matches!(event, Event::Collision) {
        "AUTO"
    } else {
        "MANUEL"
    };
    let methode = if occ.given("SUBD_METHODE") {
        occ.text("SUBD_METHODE").unwrap_or(default)
    } else {
        default
    };
    Ok(match methode {
        "MANUEL" => Subdivision::Manuel {
            subd_pas: int("SUBD_PAS", 4).max(2) as usize,
            subd_niveau: int("SUBD_NIVEAU", 3).max(2) as usize,
            subd_pas_mini: pas_mini,
        },
        _ if *event == Event::Collision => Subdivision::AutoCollision {
            subd_inst: occ
                .real("SUBD_INST")
                .ok_or_else(|| occ.error("SUBD_INST", "SUBD_INST is required"))?,
            subd_duree: occ
                .real("SUBD_DUREE")
                .ok_or_else(|| occ.error("SUBD_DUREE", "SUBD_DUREE is required"))?,
        },
        _ => Subdivision::AutoExtrapole {
            subd_pas_mini: pas_mini,
        },
    })
}

/// One ADAPTATION occurrence (METHODE='AUTO').
fn adaptation_rule(occ: &Args) -> Result<Adaptation, Diagnostic> {
    let text = |k: &str, d: &str| occ.text(k).unwrap_or(d).to_string();
    let event = match occ.text("EVENEMENT").unwrap_or("SEUIL") {
        "SEUIL" => AdaptEvent::Seuil {
            nb_incr_seuil: occ.int("NB_INCR_SEUIL").unwrap_or(2).max(1) as usize,
            nom_para: text("NOM_PARA", "NB_ITER_NEWTON"),
            crit_comp: text("CRIT_COMP", "LE"),
            vale_i: occ.int("VALE_I"),
        },
        "TOUT_INST" => AdaptEvent::ToutInst,
        _ => AdaptEvent::Aucun,
    };
    let mode = match occ.text("MODE_CALCUL_TPLUS").unwrap_or("FIXE") {
        "FIXE" => TplusMode::Fixe {
            pcent_augm: occ.real("PCENT_AUGM").unwrap_or(100.0),
        },
        "DELTA_GRANDEUR" => TplusMode::DeltaGrandeur {
            vale_ref: occ
                .real("VALE_REF")
                .ok_or_else(|| occ.error("VALE_REF", "VALE_REF is required"))?,
            nom_cham: text("NOM_CHAM", ""),
            nom_cmp: text("NOM_CMP", ""),
        },
        "ITER_NEWTON" => TplusMode::IterNewton {
            nb_iter_newton_ref: occ
                .int("NB_ITER_NEWTON_REF")
                .ok_or_else(|| occ.error("NB_ITER_NEWTON_REF", "NB_ITER_NEWTON_REF is required"))?,
        },
        _ => TplusMode::Implex,
    };
    Ok(Adaptation { event, mode })
}

/// Manual cutting: equal sub-steps, a maximum level, a minimum step.
fn bloc_manu() -> Keyword {
    block(
        "b_deco_manu",
        eq("SUBD_METHODE", "MANUEL"),
        vec![
            int("SUBD_PAS")
                .default(i(4))
                .min_val(2.0)
                .doc("number of equal sub-steps a failed step is cut into")
                .kw(),
            int("SUBD_NIVEAU")
                .default(i(3))
                .min_val(2.0)
                .doc("maximum subdivision level (the original steps are level 1)")
                .kw(),
            real("SUBD_PAS_MINI")
                .default(r(0.0))
                .min_val(0.0)
                .doc("cutting fails below this step")
                .kw(),
        ],
    )
    .rules(vec![au_moins_un(&["SUBD_NIVEAU", "SUBD_PAS_MINI"])])
    .kw()
}

/// Automatic cutting (extrapolation of the residuals).
fn bloc_auto() -> Keyword {
    block(
        "b_deco_auto",
        eq("SUBD_METHODE", "AUTO"),
        vec![real("SUBD_PAS_MINI")
            .default(r(0.0))
            .min_val(0.0)
            .doc("cutting fails below this step")
            .kw()],
    )
    .kw()
}

/// DECOUPE for the failure events: method defaults to MANUEL.
fn bloc_deco(cond: Cond) -> Keyword {
    block(
        "b_deco",
        cond,
        vec![
            text("SUBD_METHODE")
                .into(&["MANUEL", "AUTO"])
                .default(t("MANUEL"))
                .doc("how the failed step is cut")
                .kw(),
            bloc_manu(),
            bloc_auto(),
        ],
    )
    .kw()
}

fn echec() -> Keyword {
    let action = |choices: &[&'static str], default: &'static str| {
        text("ACTION")
            .into(choices)
            .default(t(default))
            .doc("what to do when the event occurs")
            .kw()
    };
    fact(
        "ECHEC",
        vec![
            text("EVENEMENT")
                .into(&[
                    "ERREUR",
                    "DELTA_GRANDEUR",
                    "COLLISION",
                    "RESI_MAXI",
                    "INTERPENETRATION",
                    "DIVE_RESI",
                    "INSTABILITE",
                ])
                .default(t("ERREUR"))
                .doc("ERREUR is any failure of a step (Newton not converged, law failure, singular matrix...)")
                .kw(),
            block(
                "b_erreur",
                eq("EVENEMENT", "ERREUR"),
                vec![
                    action(&["ARRET", "DECOUPE", "ITER_SUPPL", "AUTRE_PILOTAGE"], "DECOUPE"),
                    bloc_deco(is_in("ACTION", &["DECOUPE", "AUTRE_PILOTAGE"])),
                    block(
                        "b_supp",
                        eq("ACTION", "ITER_SUPPL"),
                        vec![
                            int("PCENT_ITER_PLUS")
                                .default(i(50))
                                .min_val(20.0)
                                .doc("extra Newton iterations allowed, in percent")
                                .kw(),
                            text("SUBD_METHODE")
                                .into(&["MANUEL", "AUTO"])
                                .default(t("MANUEL"))
                                .kw(),
                            bloc_manu(),
                            bloc_auto(),
                        ],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_edelta",
                eq("EVENEMENT", "DELTA_GRANDEUR"),
                vec![
                    real("VALE_REF").required().doc("threshold on the increment").kw(),
                    text("NOM_CHAM")
                        .required()
                        .into(&["DEPL", "VARI_ELGA", "SIEF_ELGA"])
                        .kw(),
                    text("NOM_CMP").required().kw(),
                    action(&["ARRET", "DECOUPE"], "DECOUPE"),
                    bloc_deco(eq("ACTION", "DECOUPE")),
                ],
            )
            .kw(),
            block(
                "b_colli",
                eq("EVENEMENT", "COLLISION"),
                vec![
                    action(&["ARRET", "DECOUPE"], "DECOUPE"),
                    block(
                        "b_deco2",
                        eq("ACTION", "DECOUPE"),
                        vec![
                            text("SUBD_METHODE")
                                .into(&["MANUEL", "AUTO"])
                                .default(t("AUTO"))
                                .doc("for a collision AUTO refines the steps for SUBD_DUREE")
                                .kw(),
                            bloc_manu(),
                            block(
                                "b_deco_auto",
                                eq("SUBD_METHODE", "AUTO"),
                                vec![
                                    real("SUBD_INST")
                                        .required()
                                        .min_val(0.0)
                                        .doc("target step during the collision")
                                        .kw(),
                                    real("SUBD_DUREE")
                                        .required()
                                        .min_val(0.0)
                                        .doc("duration of the refinement after a collision starts")
                                        .kw(),
                                ],
                            )
                            .kw(),
                        ],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_resi_maxi",
                eq("EVENEMENT", "RESI_MAXI"),
                vec![
                    real("RESI_GLOB_MAXI")
                        .required()
                        .doc("residual above which the step is cut")
                        .kw(),
                    action(&["ARRET", "DECOUPE"], "DECOUPE"),
                    bloc_deco(eq("ACTION", "DECOUPE")),
                ],
            )
            .kw(),
            block(
                "b_penetration",
                eq("EVENEMENT", "INTERPENETRATION"),
                vec![
                    real("PENE_MAXI")
                        .required()
                        .doc("largest allowed penetration of discrete contact")
                        .kw(),
                    action(&["ARRET", "ADAPT_COEF_PENA"], "ADAPT_COEF_PENA"),
                    block(
                        "b_pene",
                        eq("ACTION", "ADAPT_COEF_PENA"),
                        vec![real("COEF_MAXI")
                            .default(r(1e12))
                            .min_val(1.0)
                            .doc("cap of E_N, doubled at each event")
                            .kw()],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_dive_resi",
                eq("EVENEMENT", "DIVE_RESI"),
                vec![
                    action(&["DECOUPE"], "DECOUPE"),
                    bloc_deco(eq("ACTION", "DECOUPE")),
                ],
            )
            .kw(),
            block(
                "b_instabilite",
                eq("EVENEMENT", "INSTABILITE"),
                vec![action(&["ARRET", "CONTINUE"], "CONTINUE")],
            )
            .kw(),
        ],
    )
    .defaulted()
    .many()
    .doc("failure events and actions; an ERREUR event (DECOUPE, 4 sub-steps, 3 levels) always exists")
    .kw()
}

fn adaptation() -> Keyword {
    fact(
        "ADAPTATION",
        vec![
            text("EVENEMENT")
                .into(&["SEUIL", "TOUT_INST", "AUCUN"])
                .default(t("SEUIL"))
                .doc("when the next step may grow")
                .kw(),
            block(
                "b_adap_seuil",
                eq("EVENEMENT", "SEUIL"),
                vec![
                    int("NB_INCR_SEUIL").default(i(2)).kw(),
                    text("NOM_PARA")
                        .into(&["NB_ITER_NEWTON"])
                        .default(t("NB_ITER_NEWTON"))
                        .kw(),
                    text("CRIT_COMP")
                        .into(&["LT", "GT", "LE", "GE"])
                        .default(t("LE"))
                        .kw(),
                    block(
                        "b_vale_I",
                        eq("NOM_PARA", "NB_ITER_NEWTON"),
                        vec![int("VALE_I").kw()],
                    )
                    .kw(),
                ],
            )
            .kw(),
            text("MODE_CALCUL_TPLUS")
                .into(&["FIXE", "DELTA_GRANDEUR", "ITER_NEWTON", "IMPLEX"])
                .default(t("FIXE"))
                .doc("how the next step is computed")
                .kw(),
            block(
                "b_mfixe",
                eq("MODE_CALCUL_TPLUS", "FIXE"),
                vec![real("PCENT_AUGM")
                    .default(r(100.0))
                    .min_val(-100.0)
                    .doc("growth of the step, in percent")
                    .kw()],
            )
            .kw(),
            block(
                "b_mdelta",
                eq("MODE_CALCUL_TPLUS", "DELTA_GRANDEUR"),
                vec![
                    real("VALE_REF").required().kw(),
                    text("NOM_CHAM")
                        .required()
                        .into(&["DEPL", "VARI_ELGA", "SIEF_ELGA"])
                        .kw(),
                    text("NOM_CMP").required().kw(),
                ],
            )
            .kw(),
            block(
                "b_mitnew",
                eq("MODE_CALCUL_TPLUS", "ITER_NEWTON"),
                vec![int("NB_ITER_NEWTON_REF").required().kw()],
            )
            .kw(),
        ],
    )
    .defaulted()
    .many()
    .doc("step growth after successful steps (METHODE='AUTO')")
    .kw()
}
