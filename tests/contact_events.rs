//! The DEFI_LIST_INST events that concern contact, in DYNA_NON_LINE
//! (semantics.md §7.2, docs/dynamics.md): COLLISION with SUBD_METHODE='AUTO',
//! INTERPENETRATION with ADAPT_COEF_PENA, and the step growth of
//! METHODE='AUTO'.
//!
//! The case is an elastic Taylor bar (AXIS, 2 × 8 QUAD8) landing flat on
//! its rigid foundation at 10 m/s: the gap (2.27 mm) closes in the middle
//! of the list step [−1e-7, 1e-7], and the bar leaves the foundation after
//! about 2L/c ≈ 18 µs. The references are the step sequences the rules
//! define, worked out by hand, and the penalty law (penetration RN/E_N).

mod dynamics_support;

use aster::concepts::{ConceptData, ConceptType};
use aster::mesh::ops::{orie_peau, OrieDim};
use aster::model::Dof;
use aster::result::{EvolNoli, NodalField};
use aster::time::list::{
    Action, AdaptEvent, Adaptation, Event, FailureRule, Subdivision, TimeList, TplusMode,
};
use dynamics_support::*;

const V: f64 = -1.0e4;
/// Start of the list step in which the gap closes (it closes at t = 0).
const T_C: f64 = -1e-7;
const SUBD_INST: f64 = 5e-8;
/// Longer than the contact (≈ 18 µs), so that no collision starts again.
const SUBD_DUREE: f64 = 2.2e-5;

/// The list: the flight, steps of 2e-7 until T_C + SUBD_DUREE = 2.19e-5,
/// then 8 steps of 1e-6 to 2.99e-5.
fn instants() -> Vec<f64> {
    let mut t = vec![2.27 / V, T_C];
    t.extend((1..=110).map(|k| T_C + k as f64 * 2e-7));
    t.extend((1..=8).map(|k| 2.19e-5 + k as f64 * 1e-6));
    t
}

fn collision_rule() -> FailureRule {
    FailureRule {
        event: Event::Collision,
        action: Action::Decoupe(Subdivision::AutoCollision {
            subd_inst: SUBD_INST,
            subd_duree: SUBD_DUREE,
        }),
    }
}

fn time_list(instants: Vec<f64>, rules: Vec<FailureRule>, auto: Option<Option<f64>>) -> TimeList {
    let mut l = TimeList::plain(instants);
    l.rules = vec![TimeList::implicit_error_rule()];
    l.rules.extend(rules);
    if let Some(pas_maxi) = auto {
        l.auto = true;
        l.pas_maxi = pas_maxi;
        l.adaptation = vec![Adaptation {
            event: AdaptEvent::ToutInst,
            mode: TplusMode::Fixe { pcent_augm: 100.0 },
        }];
    }
    l
}

struct Landed {
    result: EvolNoli,
    slaves: Vec<usize>,
    mess: String,
}

impl Landed {
    fn insts(&self) -> Vec<f64> {
        self.result.steps.iter().map(|s| s.inst).collect()
    }
    fn cont(&self, step: usize, node: usize, cmp: &str) -> f64 {
        self.result.steps[step].nodal["CONT_NOEU"]
            .get(node, cmp)
            .unwrap()
    }
    fn in_contact(&self, step: usize) -> bool {
        self.slaves
            .iter()
            .any(|&n| self.cont(step, n, "CONT") > 0.0)
    }
    /// The largest penetration −JEU over every stored step and slave node.
    fn max_penetration(&self) -> f64 {
        (0..self.result.steps.len())
            .flat_map(|s| self.slaves.iter().map(move |&n| (s, n)))
            .map(|(s, n)| -self.cont(s, n, "JEU"))
            .fold(0.0, f64::max)
    }
}

/// Runs the landing with the time list `list`; Err: the run stopped.
fn land(list: TimeList, e_n: f64) -> Result<Landed, String> {
    let mut mesh = taylor_axis(2, 8);
    orie_peau(&mut mesh, OrieDim::D2, &["SZZ", "RIGID"], None).unwrap();
    let vol = mesh.cell_groups["VOL"].clone();
    let bar_nodes = mesh.nodes_of_cells(&vol);
    let axe = mesh.nodes_of_cells(&mesh.cell_groups["AXE"]);
    let slaves = mesh.nodes_of_cells(&mesh.cell_groups["SZZ"]);
    let mo = model(&mesh, "AXIS", &vol);
    let mut v0 = NodalField::absent(vec!["DX".into(), "DY".into()], mesh.nnodes());
    for &n in &bar_nodes {
        v0.set(n, 0, 0.0);
        v0.set(n, 1, V);
    }
    let mut st = study(
        mesh.clone(),
        mo,
        material(117000.0, 0.0, 8.93e-9, None),
        imposed(&axe, Dof::Dx, 0.0),
        Some(v0),
        list.instants.clone(),
        Some(list),
    );
    let text = format!(
        "CONT = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE', REAC_GEOM='CONTROLE', NB_ITER_GEOM=2,
    ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', ALGO_CONT='PENALISATION', E_N={e_n:e}))
RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), CONTACT=CONT,
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'),
    ETAT_INIT=_F(VITE=V0),
    INCREMENT=_F(LIST_INST=LI),
    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', BETA=0.3025, GAMMA=0.6, FORMULATION='DEPLACEMENT'),
    CONVERGENCE=_F(RESI_GLOB_RELA=1.E-8, ITER_GLOB_MAXI=30))"
    );
    insert(
        &mut st,
        "CONT",
        ConceptType::CharContact,
        ConceptData::Contact(Box::new(args_of(&text, "DEFI_CONTACT", 0))),
    );
    exec(
        &mut st,
        "DYNA_NON_LINE",
        &args_of(&text, "DYNA_NON_LINE", 0),
        "RESU",
    )
    .map_err(|e| format!("{e}\n{}", st.mess))?;
    Ok(Landed {
        result: result(&st, "RESU").clone(),
        slaves,
        mess: st.mess.clone(),
    })
}

fn assert_close(got: &[f64], want: &[f64], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: {got:?}");
    for (k, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() < 1e-15,
            "{what}: instant {k} is {g:e}, expected {w:e}"
        );
    }
}

/// COLLISION: the list step that closes the gap is redone in
/// round(2e-7 / SUBD_INST) = 4 sub-steps, the refinement goes on at
/// SUBD_INST until T_C + SUBD_DUREE (440 sub-steps in all), the links
/// whose collision runs do not cut again, and the list's own steps of
/// 1e-6 follow once the window is over and the bar has left.
#[test]
fn collision_cuts_the_closing_step_and_refines_for_subd_duree() {
    let run = land(time_list(instants(), vec![collision_rule()], None), 1e7).unwrap();
    let mut want = vec![2.27 / V, T_C];
    want.extend((1..=440).map(|k| T_C + k as f64 * SUBD_INST));
    want.extend((1..=8).map(|k| 2.19e-5 + k as f64 * 1e-6));
    assert_close(&run.insts(), &want, "instants");
    // The gap is open at T_C and closed 2 sub-steps later (t = 0 + 5e-8).
    assert!(!run.in_contact(1));
    assert!(run.in_contact(4));
    // The bar has left before the window ends: nothing to trigger again.
    for s in 441..run.result.steps.len() {
        assert!(
            !run.in_contact(s),
            "contact at {:e}",
            run.result.steps[s].inst
        );
    }
    assert_eq!(run.mess.matches("COLLISION of").count(), 1, "{}", run.mess);
    assert!(
        run.mess.contains("cut into 4 sub-steps of 5.000e-8"),
        "{}",
        run.mess
    );
}

/// METHODE='AUTO' (ADAPTATION TOUT_INST, FIXE 100 %): after the collision
/// window the step doubles from SUBD_INST (1e-7, 2e-7, 4e-7) but never
/// passes the next list instant (2.29e-5, reached by a shortened 3e-7);
/// as in code_aster (nmadat) a shortened step does not become dt⁻, so the
/// next one is 8e-7 (twice 4e-7, not twice 3e-7), then 1.6e-6 shortened
/// to each list instant 1e-6 apart. With PAS_MAXI = 2.5e-7 it stops
/// growing at PAS_MAXI. Every list instant is reached.
#[test]
fn auto_list_grows_the_step_back_up_to_the_list_and_pas_maxi() {
    let grown = land(
        time_list(instants(), vec![collision_rule()], Some(None)),
        1e7,
    )
    .unwrap();
    let t = grown.insts();
    let w = 2.19e-5;
    let k = t.iter().position(|&x| (x - w).abs() < 1e-15).unwrap();
    assert_eq!(k, 441, "the window is refined as with METHODE='MANUEL'");
    assert_close(
        &t[k..k + 9],
        &[
            w,
            w + 1e-7,
            w + 3e-7,
            w + 7e-7,
            2.29e-5,
            2.37e-5,
            2.39e-5,
            2.49e-5,
            2.59e-5,
        ],
        "AUTO",
    );
    for l in instants() {
        assert!(t.iter().any(|&x| (x - l).abs() < 1e-15), "{l:e} missed");
    }
    // No step is longer than twice the longest one before it.
    let mut longest = t[1] - t[0];
    for p in t.windows(2).skip(1) {
        assert!(p[1] - p[0] <= 2.0 * longest * (1.0 + 1e-9));
        longest = longest.max(p[1] - p[0]);
    }
    let capped = land(
        time_list(instants(), vec![collision_rule()], Some(Some(2.5e-7))),
        1e7,
    )
    .unwrap();
    let t = capped.insts();
    assert_close(
        &t[k..k + 6],
        &[w, w + 1e-7, w + 3e-7, w + 5.5e-7, w + 8e-7, 2.29e-5],
        "AUTO with PAS_MAXI",
    );
    assert!(t[k..]
        .windows(2)
        .all(|p| p[1] - p[0] <= 2.5e-7 * (1.0 + 1e-9)));
}

/// NB_PAS_MAXI ends a METHODE='AUTO' computation after that many steps,
/// as at the list's last instant (code_aster's ADAPTATION_13, an
/// information): the state of the 30th step is archived, the run ends
/// without error, and the .mess says so.
#[test]
fn nb_pas_maxi_ends_an_auto_computation() {
    let mut list = time_list(instants(), vec![collision_rule()], Some(None));
    list.nb_pas_maxi = 30;
    let run = land(list, 1e7).unwrap();
    let t = run.insts();
    assert_eq!(
        t.len(),
        31,
        "the initial state and 30 steps (every one archived)"
    );
    assert!(
        run.mess.contains("NB_PAS_MAXI = 30 steps reached"),
        "{}",
        run.mess
    );
    let full = land(
        time_list(instants(), vec![collision_rule()], Some(None)),
        1e7,
    )
    .unwrap();
    assert!(full.insts().len() > 31);
    assert_close(
        &t,
        &full.insts()[..31],
        "the first 30 steps of the full run",
    );
}

/// A PAS_MAXI below the resolution of the instants makes a step that does
/// not advance the time: the run stops saying so (it failed before as a
/// non-finite residual, cut to nothing).
#[test]
fn a_step_that_does_not_advance_the_time_stops_the_run() {
    let list = time_list(instants(), vec![], Some(Some(1e-25)));
    let Err(m) = land(list, 1e7) else {
        panic!("the run went on")
    };
    assert!(
        m.contains("does not advance the time") && m.contains("cutting the step cannot cure it"),
        "{m}"
    );
}

fn short_list() -> Vec<f64> {
    let mut t = vec![2.27 / V, T_C];
    t.extend((1..=10).map(|k| T_C + k as f64 * 2e-7));
    t
}

/// INTERPENETRATION / ADAPT_COEF_PENA: with E_N = 1e5 the bar penetrates
/// far deeper than PENE_MAXI = 2e-4 mm; with the event the steps are redone
/// with E_N doubled until the penetration (≈ RN/E_N) is within PENE_MAXI,
/// so no stored gap is below −PENE_MAXI. Doubling stops at COEF_MAXI; with
/// a cap too low the run stops on the ERREUR rule.
#[test]
fn interpenetration_doubles_e_n_until_the_penetration_is_small() {
    let pene_maxi = 2e-4;
    let soft = land(time_list(short_list(), vec![], None), 1e5).unwrap();
    assert!(
        soft.max_penetration() > 5.0 * pene_maxi,
        "{}",
        soft.max_penetration()
    );
    let rule = |coef_maxi| FailureRule {
        event: Event::Interpenetration { pene_maxi },
        action: Action::AdaptCoefPena { coef_maxi },
    };
    let run = land(time_list(short_list(), vec![rule(1e9)], None), 1e5).unwrap();
    let p = run.max_penetration();
    assert!(p > 0.0 && p <= pene_maxi, "max penetration {p:e}");
    assert_close(&run.insts(), &short_list(), "instants");
    // Each redo doubles E_N: 1e5 -> 2e5 -> 4e5 ...
    let doublings: Vec<&str> = run
        .mess
        .lines()
        .filter(|l| l.contains("ADAPT_COEF_PENA:"))
        .collect();
    assert!(!doublings.is_empty());
    let mut e = 1e5;
    for d in &doublings {
        assert!(d.contains(&format!("E_N {e:e} -> {:e}", 2.0 * e)), "{d}");
        e *= 2.0;
    }
    eprintln!(
        "INTERPENETRATION: {} doublings, E_N 1e5 -> {e:e}, max penetration {:.3e} -> {p:.3e}",
        doublings.len(),
        soft.max_penetration()
    );
    // The penetration went down with 1/E_N: the softer run's maximum over
    // the final E_N is of the order of the adapted one.
    assert!(soft.max_penetration() * 1e5 / e <= pene_maxi * 1.5);
    let Err(err) = land(time_list(short_list(), vec![rule(4e5)], None), 1e5) else {
        panic!("the run must stop when E_N reaches COEF_MAXI");
    };
    assert!(err.contains("COEF_MAXI = 4e5"), "{err}");
}
