//! The time list of a transient computation (DEFI_LIST_INST, or a plain
//! DEFI_LIST_REEL) and the failure events that drive step cutting.

/// What happens when a step fails or an event is detected.
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    /// Stop the computation (results archived so far are kept).
    Arret,
    /// Cut the step.
    Decoupe(Subdivision),
    /// Multiply the contact penalty coefficient (ADAPT_COEF_PENA).
    AdaptCoefPena { coef_maxi: f64 },
    /// Extra Newton iterations (ITER_SUPPL), in percent of ITER_GLOB_MAXI;
    /// when extrapolation predicts no convergence the step is cut as
    /// `subdivision` says.
    IterSuppl {
        pcent_iter_plus: f64,
        subdivision: Subdivision,
    },
    /// INSTABILITE with ACTION='CONTINUE': report and go on.
    Continue,
}

impl std::fmt::Display for Action {
    /// code_aster's keywords, for the message file.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Action::Arret => f.write_str("ARRET"),
            Action::Decoupe(s) => write!(f, "DECOUPE {s}"),
            Action::AdaptCoefPena { coef_maxi } => {
                write!(f, "ADAPT_COEF_PENA (COEF_MAXI={coef_maxi:e})")
            }
            Action::IterSuppl {
                pcent_iter_plus,
                subdivision,
            } => write!(
                f,
                "ITER_SUPPL (PCENT_ITER_PLUS={pcent_iter_plus}), then DECOUPE {subdivision}"
            ),
            Action::Continue => f.write_str("CONTINUE"),
        }
    }
}

impl std::fmt::Display for Subdivision {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Subdivision::Manuel {
                subd_pas,
                subd_niveau,
                subd_pas_mini,
            } => write!(
                f,
                "MANUEL (SUBD_PAS={subd_pas}, SUBD_NIVEAU={subd_niveau}, SUBD_PAS_MINI={})",
                short(*subd_pas_mini)
            ),
            Subdivision::AutoCollision {
                subd_inst,
                subd_duree,
            } => write!(
                f,
                "AUTO (SUBD_INST={subd_inst:e}, SUBD_DUREE={subd_duree:e})"
            ),
            Subdivision::AutoExtrapole { subd_pas_mini } => {
                write!(
                    f,
                    "AUTO extrapolated (SUBD_PAS_MINI={})",
                    short(*subd_pas_mini)
                )
            }
        }
    }
}

/// 0 as "0", other reals in exponent notation (steps and tolerances).
fn short(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else {
        format!("{v:e}")
    }
}

/// How a step is cut.
#[derive(Debug, Clone, PartialEq)]
pub enum Subdivision {
    /// SUBD_METHODE='MANUEL': SUBD_PAS equal sub-steps, at most SUBD_NIVEAU
    /// levels, never below SUBD_PAS_MINI.
    Manuel {
        subd_pas: usize,
        subd_niveau: usize,
        subd_pas_mini: f64,
    },
    /// SUBD_METHODE='AUTO' for COLLISION: sub-steps of SUBD_INST during
    /// SUBD_DUREE.
    AutoCollision { subd_inst: f64, subd_duree: f64 },
    /// SUBD_METHODE='AUTO' for other events (extrapolation of the
    /// residual), never below SUBD_PAS_MINI.
    AutoExtrapole { subd_pas_mini: f64 },
}

impl Subdivision {
    /// SUBD_PAS_MINI of the methods that have one.
    pub fn subd_pas_mini(&self) -> Option<f64> {
        match self {
            Subdivision::Manuel { subd_pas_mini, .. }
            | Subdivision::AutoExtrapole { subd_pas_mini } => Some(*subd_pas_mini),
            Subdivision::AutoCollision { .. } => None,
        }
    }
}

/// The events of DEFI_LIST_INST ECHEC.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// Any failure of the step: Newton not converged, law integration
    /// failure, singular matrix.
    Erreur,
    Collision,
    Interpenetration {
        pene_maxi: f64,
    },
    /// The increment of a component over the step exceeds VALE_REF.
    DeltaGrandeur {
        vale_ref: f64,
        nom_cham: String,
        nom_cmp: String,
    },
    /// The residual exceeds RESI_GLOB_MAXI during Newton.
    ResiMaxi {
        resi_glob_maxi: f64,
    },
    /// Events without parameters: DIVE_RESI, INSTABILITE.
    Other(String),
}

impl Event {
    /// code_aster's EVENEMENT name.
    pub fn name(&self) -> &str {
        match self {
            Event::Erreur => "ERREUR",
            Event::Collision => "COLLISION",
            Event::Interpenetration { .. } => "INTERPENETRATION",
            Event::DeltaGrandeur { .. } => "DELTA_GRANDEUR",
            Event::ResiMaxi { .. } => "RESI_MAXI",
            Event::Other(n) => n,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct FailureRule {
    pub event: Event,
    pub action: Action,
}

impl FailureRule {
    /// SUBD_PAS_MINI of the rule's cutting method, if it has one.
    pub fn action_subd_pas_mini(&self) -> Option<f64> {
        match &self.action {
            Action::Decoupe(s) | Action::IterSuppl { subdivision: s, .. } => s.subd_pas_mini(),
            _ => None,
        }
    }
}

/// The result of DEFI_LIST_INST (or the view of a DEFI_LIST_REEL used as
/// INCREMENT/LIST_INST, which has no rule but ERREUR -> ARRET).
#[derive(Debug, Clone, PartialEq)]
pub struct TimeList {
    pub instants: Vec<f64>,
    /// METHODE='AUTO': the step may grow back after success.
    pub auto: bool,
    /// For METHODE='AUTO': PAS_MINI, PAS_MAXI, NB_PAS_MAXI.
    pub pas_mini: Option<f64>,
    pub pas_maxi: Option<f64>,
    pub nb_pas_maxi: usize,
    pub rules: Vec<FailureRule>,
    /// METHODE='AUTO': when and how the step grows (ADAPTATION); empty for
    /// a manual list.
    pub adaptation: Vec<Adaptation>,
}

/// When the next step may grow (ADAPTATION/EVENEMENT).
#[derive(Debug, Clone, PartialEq)]
pub enum AdaptEvent {
    /// After NB_INCR_SEUIL consecutive steps whose NOM_PARA (the number of
    /// Newton iterations) compares to VALE_I with CRIT_COMP. `vale_i` None:
    /// not given, the solver's default applies.
    Seuil {
        nb_incr_seuil: usize,
        nom_para: String,
        crit_comp: String,
        vale_i: Option<i64>,
    },
    /// After every step.
    ToutInst,
    /// Never.
    Aucun,
}

/// How the next step is computed (ADAPTATION/MODE_CALCUL_TPLUS).
#[derive(Debug, Clone, PartialEq)]
pub enum TplusMode {
    /// The step grows by PCENT_AUGM percent.
    Fixe {
        pcent_augm: f64,
    },
    DeltaGrandeur {
        vale_ref: f64,
        nom_cham: String,
        nom_cmp: String,
    },
    IterNewton {
        nb_iter_newton_ref: i64,
    },
    Implex,
}

/// One ADAPTATION occurrence.
#[derive(Debug, Clone, PartialEq)]
pub struct Adaptation {
    pub event: AdaptEvent,
    pub mode: TplusMode,
}

impl TimeList {
    /// A plain list of instants: a failure stops the computation.
    pub fn plain(instants: Vec<f64>) -> Self {
        TimeList {
            instants,
            auto: false,
            pas_mini: None,
            pas_maxi: None,
            nb_pas_maxi: 1_000_000,
            rules: vec![FailureRule {
                event: Event::Erreur,
                action: Action::Arret,
            }],
            adaptation: Vec::new(),
        }
    }

    /// The ERREUR rule DEFI_LIST_INST adds when the user gives none
    /// (semantics.md §7.2): cut in 4, at most 3 levels, never below 1e-12.
    /// Its SUBD_PAS_MINI is not the catalogue default 0.
    pub fn implicit_error_rule() -> FailureRule {
        FailureRule {
            event: Event::Erreur,
            action: Action::Decoupe(Subdivision::Manuel {
                subd_pas: 4,
                subd_niveau: 3,
                subd_pas_mini: 1e-12,
            }),
        }
    }

    /// The smallest step of the list (None with fewer than two instants).
    pub fn min_step(&self) -> Option<f64> {
        self.instants
            .windows(2)
            .map(|w| w[1] - w[0])
            .min_by(f64::total_cmp)
    }

    /// The maximum subdivision level that applies to **every** event.
    ///
    /// code_aster keeps one level counter per step, shared by all events
    /// that cut it, and compares it with the largest SUBD_NIVEAU of all the
    /// MANUEL cutting rules (ERREUR, COLLISION, DELTA_GRANDEUR...; also the
    /// fallback cut of ITER_SUPPL): a rule with SUBD_NIVEAU=2 next to one
    /// with 5 may cut 5 levels deep. The original steps are level 1, so the
    /// smallest step a level limit allows is dt / SUBD_PAS^(level - 1).
    /// None when no rule cuts manually, or with METHODE='AUTO', where the
    /// level notion does not exist (only the SUBD_PAS_MINI and PAS_MINI
    /// limits apply).
    pub fn max_subd_niveau(&self) -> Option<usize> {
        if self.auto {
            return None;
        }
        self.rules
            .iter()
            .filter_map(|r| match &r.action {
                Action::Decoupe(Subdivision::Manuel { subd_niveau, .. })
                | Action::IterSuppl {
                    subdivision: Subdivision::Manuel { subd_niveau, .. },
                    ..
                } => Some(*subd_niveau),
                _ => None,
            })
            .max()
    }

    /// The rule for the ERREUR event (there is always one).
    pub fn on_error(&self) -> &Action {
        self.rules
            .iter()
            .find(|r| r.event == Event::Erreur)
            .map(|r| &r.action)
            .unwrap_or(&Action::Arret)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn manuel(subd_niveau: usize) -> Subdivision {
        Subdivision::Manuel {
            subd_pas: 2,
            subd_niveau,
            subd_pas_mini: 0.0,
        }
    }

    /// The level limit is the largest SUBD_NIVEAU of any MANUEL cutting
    /// rule, the ITER_SUPPL fallback included; AUTO cutting has no level;
    /// METHODE='AUTO' has none at all.
    #[test]
    fn shared_subdivision_level() {
        let mut l = TimeList::plain(vec![0.0, 0.1, 0.3]);
        assert_eq!(l.max_subd_niveau(), None);
        l.rules = vec![
            FailureRule {
                event: Event::Erreur,
                action: Action::IterSuppl {
                    pcent_iter_plus: 50.0,
                    subdivision: manuel(6),
                },
            },
            FailureRule {
                event: Event::Collision,
                action: Action::Decoupe(manuel(2)),
            },
            FailureRule {
                event: Event::ResiMaxi {
                    resi_glob_maxi: 1.0,
                },
                action: Action::Decoupe(Subdivision::AutoExtrapole { subd_pas_mini: 0.0 }),
            },
        ];
        assert_eq!(l.max_subd_niveau(), Some(6));
        l.auto = true;
        assert_eq!(l.max_subd_niveau(), None);
        assert!((l.min_step().unwrap() - 0.1).abs() < 1e-15);
        assert_eq!(TimeList::plain(vec![1.0]).min_step(), None);
    }

    #[test]
    fn implicit_rule_and_its_text() {
        let r = TimeList::implicit_error_rule();
        assert_eq!(r.action_subd_pas_mini(), Some(1e-12));
        assert_eq!(
            r.action.to_string(),
            "DECOUPE MANUEL (SUBD_PAS=4, SUBD_NIVEAU=3, SUBD_PAS_MINI=1e-12)"
        );
    }
}
