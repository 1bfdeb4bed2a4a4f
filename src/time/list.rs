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
    /// Extra Newton iterations (ITER_SUPPL), in percent of ITER_GLOB_MAXI.
    IterSuppl { pcent_iter_plus: f64 },
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
    /// SUBD_METHODE='AUTO' for other events (extrapolation of the residual).
    AutoExtrapole,
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
    Other(String),
}

#[derive(Debug, Clone, PartialEq)]
pub struct FailureRule {
    pub event: Event,
    pub action: Action,
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
        }
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
