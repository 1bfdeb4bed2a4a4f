//! Verification of LIAISON_UNIL (DEFI_CONTACT FORMULATION='LIAISON_UNIL')
//! inside DYNA_NON_LINE (docs/contact.md, liaison-unil.md §9).
//!
//! References are independent of the unilateral code: the Newmark
//! relations of a mass stopped by an exact constraint (§9.3 a), the static
//! spring pushed by a moving floor and the 1/(k + E) law of its penalised
//! version (§9.2), the KKT conditions read back from DEPL and REAC_NODA,
//! the momentum balance of a bar dropped on the floor, and a hand-built 1D
//! Newmark bar that follows SDNV103 E's time list step by step.
#![allow(clippy::needless_range_loop)]

mod dynamics_support;

use aster::concepts::{ConceptData, ConceptType};
use aster::mesh::taylor::{generate, TaylorKind, TaylorParams};
use aster::model::{Dof, ImposedDof, MaterialField};
use aster::nonlinear::discretize;
use aster::post::function::{Extrapolation, Function};
use aster::result::EvolNoli;
use aster::study::Study;
use dynamics_support::*;

/// Declarations the checker needs for the functions a test inserts.
const FUNCTIONS: &str = "
C0 = DEFI_CONSTANTE(VALE=0.)
CM1 = DEFI_CONSTANTE(VALE=-1.)
CI = DEFI_CONSTANTE(VALE=0.)
CI2 = DEFI_CONSTANTE(VALE=0.)
CI3 = DEFI_CONSTANTE(VALE=0.)
CI4 = DEFI_CONSTANTE(VALE=0.)
CI5 = DEFI_CONSTANTE(VALE=0.)
LI2 = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=L_INST), ECHEC=_F(EVENEMENT='ERREUR', ACTION='DECOUPE', SUBD_METHODE='MANUEL', SUBD_PAS=2, SUBD_NIVEAU=3))
";

fn insert_function(st: &mut Study, name: &str, f: Function) {
    insert(
        st,
        name,
        ConceptType::Fonction,
        ConceptData::Function(Box::new(f)),
    );
}

/// h0 − w·INST, linear on both sides.
fn moving_floor(h0: f64, w: f64) -> Function {
    let mut f = Function::new("INST", "TOUTRESU", vec![0.0, 1.0], vec![h0, h0 - w]).unwrap();
    f.left = Extrapolation::Linear;
    f.right = Extrapolation::Linear;
    f
}

/// Runs DEFI_CONTACT (`zones`), DYNA_NON_LINE and CALC_CHAMP REAC_NODA
/// on a study prepared by `study`; returns the DYNA_NON_LINE outcome.
fn run(st: &mut Study, zones: &str, schema: &str, extra: &str) -> Result<(), String> {
    insert_function(st, "C0", Function::constant(0.0, "TOUTRESU"));
    insert_function(st, "CM1", Function::constant(-1.0, "TOUTRESU"));
    let text = format!(
        "{FUNCTIONS}
UNIL = DEFI_CONTACT(MODELE=MO, FORMULATION='LIAISON_UNIL', ZONE=({zones}))
RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), CONTACT=UNIL,
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'),
    ETAT_INIT=_F(VITE=V0),
    SCHEMA_TEMPS=_F({schema}),
    CONVERGENCE=_F(RESI_GLOB_RELA=1.E-10, ITER_GLOB_MAXI=20), {extra})
RESU = CALC_CHAMP(reuse=RESU, RESULTAT=RESU, FORCE=('REAC_NODA',))"
    );
    let args = args_of(&text, "DEFI_CONTACT", 0);
    let reg = aster::commands::all();
    let def = reg.iter().find(|d| d.spec.name == "DEFI_CONTACT").unwrap();
    let data = (def.exec)(st, &args, Some("UNIL"))
        .map_err(|d| d.render(None))?
        .unwrap();
    insert(st, "UNIL", ConceptType::CharContact, data);
    exec(
        st,
        "DYNA_NON_LINE",
        &args_of(&text, "DYNA_NON_LINE", 0),
        "RESU",
    )?;
    exec(st, "CALC_CHAMP", &args_of(&text, "CALC_CHAMP", 0), "RESU")
}

fn val(r: &EvolNoli, step: usize, field: &str, node: usize, cmp: &str) -> f64 {
    r.steps[step].nodal[field]
        .get(node, cmp)
        .unwrap_or_else(|| panic!("{field} {cmp} absent at node {}", node + 1))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// One QUAD8 of the axisymmetric bar with every dof blocked but DY of A1
/// (the bottom node on the axis): a single degree of freedom.
fn single_node(e: f64, rho: f64, v0: f64, instants: Vec<f64>) -> (Study, usize, f64) {
    let mut mesh = taylor_axis(1, 1);
    let vol = mesh.cell_groups["VOL"].clone();
    let nodes = mesh.nodes_of_cells(&vol);
    let a1 = mesh.node_groups["A1"][0];
    mesh.name = "MAIL".into();
    let mo = model(&mesh, "AXIS", &vol);
    let mut imp: Vec<ImposedDof> = Vec::new();
    for &n in &nodes {
        imp.push(ImposedDof {
            node: n,
            dof: Dof::Dx,
            value: 0.0,
        });
        if n != a1 {
            imp.push(ImposedDof {
                node: n,
                dof: Dof::Dy,
                value: 0.0,
            });
        }
    }
    let mat = material(e, 0.0, rho, None);
    let mass = {
        let mut mats = indexmap::IndexMap::new();
        mats.insert("MAT".to_string(), mat.clone());
        let mf = MaterialField {
            mesh: "MAIL".into(),
            cell_material: vec![Some("MAT".into()); mesh.ncells()],
        };
        let (asm, _) = discretize(&mesh, &mo, &mf, &mats, &[], &[]).unwrap();
        asm.mass_full.get(2 * a1 + 1, 2 * a1 + 1)
    };
    let v = velocity(mesh.nnodes(), &[a1], v0);
    (study(mesh, mo, mat, imp, Some(v), instants, None), a1, mass)
}

const ONE_NODE: &str = "_F(GROUP_NO='A1', NOM_CMP='DY', COEF_MULT=CM1, COEF_IMPO=CI)";

/// §9.3 (a): a free mass (stiffness 1e-9, negligible) hits the floor at
/// its initial position. Step 1 stops it exactly (u = 0) with v = +V and
/// the multiplier 4mV/Δt read back as REAC_NODA; step 2 releases it at
/// v = 3V, u = 2VΔt (the trapezoidal rule's known energy error, which a
/// faithful implementation reproduces).
#[test]
fn single_mass_impact_gives_the_exact_multiplier() {
    let (v, dt) = (1000.0, 1e-6);
    let (mut st, a1, m) = single_node(1e-9, 8.93e-9, -v, linspace(0.0, 3.0 * dt, 3));
    insert_function(&mut st, "CI", Function::constant(0.0, "TOUTRESU"));
    run(
        &mut st,
        ONE_NODE,
        "SCHEMA='NEWMARK', BETA=0.25, GAMMA=0.5, FORMULATION='DEPLACEMENT'",
        "INCREMENT=_F(LIST_INST=L_INST)",
    )
    .unwrap();
    let r = result(&st, "RESU");
    assert_eq!(val(r, 1, "DEPL", a1, "DY"), 0.0);
    assert!(rel(val(r, 1, "VITE", a1, "DY"), v) < 1e-9);
    let mu = val(r, 1, "REAC_NODA", a1, "DY");
    assert!(
        rel(mu, 4.0 * m * v / dt) < 1e-9,
        "{mu} vs {}",
        4.0 * m * v / dt
    );
    assert!(rel(val(r, 2, "DEPL", a1, "DY"), 2.0 * v * dt) < 1e-8);
    assert!(rel(val(r, 2, "VITE", a1, "DY"), 3.0 * v) < 1e-8);
    assert!(val(r, 2, "REAC_NODA", a1, "DY").abs() < 1e-9 * m * v / dt);
    // Free flight at 3V afterwards.
    assert!(rel(val(r, 3, "VITE", a1, "DY"), 3.0 * v) < 1e-8);
}

/// §9.2, quasi-static (negligible mass): a floor rising at w from h0 below
/// the node pushes it. The active set puts the node exactly on the floor
/// with a reaction proportional to the push (the spring k = μ/u); the
/// penalised condition gives μ_E = k E f/(k + E), i.e. a relative error
/// k/(k + E) that falls as 1/COEF_PENA.
#[test]
fn spring_pushed_by_a_moving_floor_exact_and_penalised() {
    let (h0, w) = (0.5, 1.0);
    let instants = linspace(0.0, 2.0, 20);
    let push = |st: &mut Study, zone: &str| {
        insert_function(st, "CI", moving_floor(h0, w));
        run(
            st,
            zone,
            "SCHEMA='NEWMARK', BETA=0.25, GAMMA=0.5, FORMULATION='DEPLACEMENT'",
            "INCREMENT=_F(LIST_INST=L_INST)",
        )
        .unwrap();
    };
    let (mut st, a1, _) = single_node(1e5, 1e-15, 0.0, instants.clone());
    push(&mut st, ONE_NODE);
    let r = result(&st, "RESU");
    let last = r.steps.len() - 1;
    let mut k = None;
    for s in 1..=last {
        let t = r.steps[s].inst;
        let (u, mu) = (
            val(r, s, "DEPL", a1, "DY"),
            val(r, s, "REAC_NODA", a1, "DY"),
        );
        let f = w * t - h0;
        if f <= 0.0 {
            assert!(mu.abs() < 1e-9, "t {t}: free node, reaction {mu}");
            assert!(u.abs() < 1e-12);
        } else {
            assert!((u - f).abs() < 1e-12, "t {t}: u {u} on the floor {f}");
            let ks = mu / u;
            let k0 = *k.get_or_insert(ks);
            assert!(rel(ks, k0) < 1e-9, "t {t}: μ/u {ks} vs {k0}");
        }
    }
    let k = k.unwrap();
    let mu_exact = val(r, last, "REAC_NODA", a1, "DY");
    let mut errors = Vec::new();
    for factor in [1e2, 1e3, 1e4] {
        let e = factor * k;
        let (mut st, _, _) = single_node(1e5, 1e-15, 0.0, instants.clone());
        let zone = format!(
            "_F(GROUP_NO='A1', NOM_CMP='DY', COEF_MULT=CM1, COEF_IMPO=CI, ALGO_CONT='PENALISATION', COEF_PENA={e:e})"
        );
        push(&mut st, &zone);
        let r = result(&st, "RESU");
        let mu = val(r, last, "REAC_NODA", a1, "DY");
        let err = (mu_exact - mu) / mu_exact;
        assert!(
            rel(err, k / (k + e)) < 1e-4,
            "E = {e:e}: error {err} vs {}",
            k / (k + e)
        );
        errors.push(err);
    }
    for p in errors.windows(2) {
        assert!(rel(p[0] / p[1], 10.0) < 0.02, "{errors:?}");
    }
}

/// A patch of nodes: the bottom of an elastic block (top held, negligible
/// mass) meets a floor rising under each bottom node with its own offset.
/// At every step every inequality, every sign and the complementarity
/// hold (read from DEPL and REAC_NODA), and within a step the active set
/// changes (more than one pass in a call).
#[test]
fn moving_floor_patch_satisfies_every_condition() {
    let mut mesh = taylor_axis(2, 2);
    mesh.name = "MAIL".into();
    let vol = mesh.cell_groups["VOL"].clone();
    let axe = mesh.nodes_of_cells(&mesh.cell_groups["AXE"]);
    let mut bottom = mesh.nodes_of_cells(&mesh.cell_groups["SZZ"]);
    bottom.sort_by(|a, b| mesh.coords[*a][0].total_cmp(&mesh.coords[*b][0]));
    assert_eq!(bottom.len(), 5);
    let nodes = mesh.nodes_of_cells(&vol);
    let top_y = mesh.coords.iter().map(|c| c[1]).fold(f64::MIN, f64::max);
    let top: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|&n| (mesh.coords[n][1] - top_y).abs() < 1e-9)
        .collect();
    for (i, &n) in bottom.iter().enumerate() {
        mesh.node_groups.insert(format!("N{i}"), vec![n]);
    }
    let mo = model(&mesh, "AXIS", &vol);
    let mut imp = imposed(&axe, Dof::Dx, 0.0);
    imp.extend(imposed(&top, Dof::Dy, 0.0));
    imp.extend(imposed(&top, Dof::Dx, 0.0));
    let v = velocity(mesh.nnodes(), &nodes, 0.0);
    let instants = linspace(0.0, 1.0, 8);
    let mut st = study(
        mesh.clone(),
        mo,
        material(1e5, 0.3, 1e-15, None),
        imp,
        Some(v),
        instants,
        None,
    );
    // Floor under node i: u_y >= w t − h_i, node 0 first; w Δt spans
    // several offsets so that several links are violated in one step.
    let (w, offsets) = (0.3, [0.0, 0.1, 0.05, 0.2, 0.15]);
    let names = ["CI", "CI2", "CI3", "CI4", "CI5"];
    let mut zones = Vec::new();
    for i in 0..5 {
        insert_function(&mut st, names[i], moving_floor(offsets[i], w));
        zones.push(format!(
            "_F(GROUP_NO='N{i}', NOM_CMP='DY', COEF_MULT=CM1, COEF_IMPO={})",
            names[i]
        ));
    }
    // The names are inserted again by `run` only for C0/CM1.
    run(
        &mut st,
        &zones.join(", "),
        "SCHEMA='NEWMARK', BETA=0.25, GAMMA=0.5, FORMULATION='DEPLACEMENT'",
        "INCREMENT=_F(LIST_INST=L_INST)",
    )
    .unwrap();
    let r = result(&st, "RESU");
    let mu_max = (1..r.steps.len())
        .flat_map(|s| bottom.iter().map(move |&n| (s, n)))
        .map(|(s, n)| val(r, s, "REAC_NODA", n, "DY").abs())
        .fold(0.0, f64::max);
    let tol = 1e-8 * mu_max;
    let mut patterns = std::collections::BTreeSet::new();
    for s in 1..r.steps.len() {
        let t = r.steps[s].inst;
        let mut pattern = Vec::new();
        for i in 0..5 {
            let n = bottom[i];
            let gap = val(r, s, "DEPL", n, "DY") - (w * t - offsets[i]);
            let mu = val(r, s, "REAC_NODA", n, "DY");
            assert!(gap >= -1e-12, "t {t} node {i}: gap {gap}");
            assert!(mu >= -tol, "t {t} node {i}: reaction {mu}");
            assert!(
                mu <= tol || gap.abs() <= 1e-12,
                "t {t} node {i}: μ {mu} with gap {gap}"
            );
            pattern.push(mu > tol);
        }
        patterns.insert(pattern);
    }
    assert!(
        patterns.len() >= 2,
        "the contact pattern never changed: {patterns:?}"
    );
    // Some nodes whose floor has risen above their initial position are
    // nevertheless free: the pushed neighbours lifted them off their floor.
    let last = r.steps.len() - 1;
    let t = r.steps[last].inst;
    let lifted = (0..5)
        .filter(|&i| {
            let n = bottom[i];
            let gap = val(r, last, "DEPL", n, "DY") - (w * t - offsets[i]);
            w * t - offsets[i] > 0.0 && gap > 1e-6 && val(r, last, "REAC_NODA", n, "DY") <= tol
        })
        .count();
    assert!(
        (1..5).contains(&lifted),
        "{lifted} nodes lifted by their neighbours"
    );
    let line = st
        .mess
        .lines()
        .find(|l| l.contains("active-set calls"))
        .expect("active-set statistics in the message file");
    let most: usize = line
        .split("at most ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .unwrap();
    assert!(most >= 2, "no active-set change inside a call: {line}");
}

/// A node listed in two zones with the same coefficients gives two
/// identical links: the Schur complement is singular (code_aster's code 2,
/// event ERRE_CTD2). The step is cut as DEFI_LIST_INST says, then the run
/// stops with a clear message at the last level.
#[test]
fn failed_active_set_cuts_the_step_then_stops() {
    let (v, dt) = (1000.0, 1e-6);
    let (mut st, _, _) = single_node(1e-9, 8.93e-9, -v, linspace(0.0, 2.0 * dt, 2));
    insert_function(&mut st, "CI", Function::constant(0.0, "TOUTRESU"));
    exec(
        &mut st,
        "DEFI_LIST_INST",
        &args_of(FUNCTIONS, "DEFI_LIST_INST", 1),
        "LI2",
    )
    .unwrap();
    let err = run(
        &mut st,
        &format!("{ONE_NODE}, {ONE_NODE}"),
        "SCHEMA='NEWMARK', BETA=0.25, GAMMA=0.5, FORMULATION='DEPLACEMENT'",
        "INCREMENT=_F(LIST_INST=LI2)",
    )
    .map(|_| ())
    .map_err(|e| e.to_string());
    let e = err.expect_err("two identical links must fail");
    assert!(
        e.contains("singular") && e.contains("MECANONLINE9_6"),
        "{e}"
    );
    let cuts = st.mess.matches("the step is cut into 2").count();
    assert_eq!(cuts, 2, "{}", st.mess);
}

/// An elastic bar (AXIS 2 × 8, ν = 0) dropped at 10 m/s on a LIAISON_UNIL
/// floor (−DY ≤ 2.27 on its bottom face): it rebounds, never goes below the
/// floor, and the change of its momentum Σ(Mv)_y equals the impulse of the
/// floor's reaction (REAC_NODA), integrated with the scheme's own
/// (1 − γ, γ) weights, within 1 %.
#[test]
fn elastic_bar_dropped_on_the_floor_conserves_momentum_exchange() {
    let (v0, dt, t_end): (f64, f64, f64) = (-1.0e4, 2e-7, 2.4e-5);
    let gamma = 0.6;
    let mut mesh = taylor_axis(2, 8);
    mesh.name = "MAIL".into();
    let vol = mesh.cell_groups["VOL"].clone();
    let nodes = mesh.nodes_of_cells(&vol);
    let axe = mesh.nodes_of_cells(&mesh.cell_groups["AXE"]);
    let szz = mesh.nodes_of_cells(&mesh.cell_groups["SZZ"]);
    let mo = model(&mesh, "AXIS", &vol);
    let mut t = vec![2.27 / v0, -dt];
    let n = ((t_end + dt) / dt).round() as usize;
    for k in 1..n {
        t.push(-dt + k as f64 * dt);
    }
    let mat = material(117000.0, 0.0, 8.93e-9, None);
    let mut st = study(
        mesh.clone(),
        mo.clone(),
        mat.clone(),
        imposed(&axe, Dof::Dx, 0.0),
        Some(velocity(mesh.nnodes(), &nodes, v0)),
        t,
        None,
    );
    insert_function(&mut st, "CI", Function::constant(2.27, "TOUTRESU"));
    run(
        &mut st,
        "_F(GROUP_MA='SZZ', NOM_CMP='DY', COEF_MULT=CM1, COEF_IMPO=CI)",
        "SCHEMA='NEWMARK', BETA=0.3025, GAMMA=0.6, FORMULATION='DEPLACEMENT'",
        "INCREMENT=_F(LIST_INST=L_INST)",
    )
    .unwrap();
    let r = result(&st, "RESU");
    let mut mats = indexmap::IndexMap::new();
    mats.insert("MAT".to_string(), mat);
    let mf = MaterialField {
        mesh: "MAIL".into(),
        cell_material: vec![Some("MAT".into()); mesh.ncells()],
    };
    let (asm, _) = discretize(&mesh, &mo, &mf, &mats, &[], &[]).unwrap();
    let momentum = |s: usize| {
        let vite = &r.steps[s].nodal["VITE"];
        let mut v = vec![0.0; 2 * mesh.nnodes()];
        for &i in &nodes {
            v[2 * i] = vite.get(i, "DX").unwrap_or(0.0);
            v[2 * i + 1] = vite.get(i, "DY").unwrap_or(0.0);
        }
        let mut mv = vec![0.0; v.len()];
        asm.mass_full.mul_vec(&v, &mut mv);
        (0..mesh.nnodes()).map(|i| mv[2 * i + 1]).sum::<f64>()
    };
    let reaction = |s: usize| {
        szz.iter()
            .map(|&i| val(r, s, "REAC_NODA", i, "DY"))
            .sum::<f64>()
    };
    let last = r.steps.len() - 1;
    let mut impulse = 0.0;
    for s in 1..=last {
        let h = r.steps[s].inst - r.steps[s - 1].inst;
        impulse += h * ((1.0 - gamma) * reaction(s - 1) + gamma * reaction(s));
        for &i in &szz {
            assert!(val(r, s, "DEPL", i, "DY") >= -2.27 - 1e-12);
        }
    }
    let (p0, p1) = (momentum(0), momentum(last));
    assert!(p0 < 0.0 && p1 > 0.0, "no rebound: {p0} -> {p1}");
    assert!(impulse > 0.0);
    assert!(
        rel(p1 - p0, impulse) < 0.01,
        "momentum change {} vs impulse {impulse}",
        p1 - p0
    );
}

/// One step of the independent reference of
/// `sdnv103e_time_list_bounce_is_newmark_and_depends_on_the_layer_height`.
struct BarState {
    u: Vec<f64>,
    v: Vec<f64>,
    /// Floor reaction on the bottom node (per radian, upward), 0 if free.
    mu: f64,
}

/// A linear bar of `n2` two-node elements (length 32.4, section `area`,
/// bottom at the floor's height + 2.27), all nodes at −`v0` at `times[0]`,
/// integrated by Newmark in displacement form with code_aster's
/// predictor (u⁰ = u_n, ndnpas) and an exact floor on the bottom node
/// (one link, so the complementarity problem is solved by hand: free
/// increment; if it goes through the floor, the bottom increment is the
/// gap and the rest is solved again). Hand-built K = EA/h [1 −1; −1 1] and
/// M = ρAh/6 [2 1; 1 2]: nothing of the engine is used.
fn bar_on_floor_reference(n2: usize, area: f64, v0: f64, times: &[f64]) -> Vec<BarState> {
    use nalgebra::{DMatrix, DVector};
    let (e, rho, beta, gamma) = (117000.0, 8.93e-9, 0.49, 0.9);
    let (n, h) = (n2 + 1, 32.4 / n2 as f64);
    let mut k = DMatrix::<f64>::zeros(n, n);
    let mut m = DMatrix::<f64>::zeros(n, n);
    for el in 0..n2 {
        for (a, b, kk, mm) in [
            (0, 0, 1.0, 2.0),
            (0, 1, -1.0, 1.0),
            (1, 0, -1.0, 1.0),
            (1, 1, 1.0, 2.0),
        ] {
            k[(el + a, el + b)] += e * area / h * kk;
            m[(el + a, el + b)] += rho * area * h / 6.0 * mm;
        }
    }
    let mut u = DVector::<f64>::zeros(n);
    let mut v = DVector::<f64>::from_element(n, -v0);
    let mut acc = DVector::<f64>::zeros(n);
    let mut out = Vec::new();
    for w in times.windows(2) {
        let dt = w[1] - w[0];
        let v_pred = &v * (1.0 - gamma / beta) + &acc * (dt * (1.0 - gamma / (2.0 * beta)));
        let a_pred = &v * (-1.0 / (beta * dt)) - &acc * (1.0 / (2.0 * beta) - 1.0);
        let c = &k + &m / (beta * dt * dt);
        let r = -(&k * &u) - &m * &a_pred;
        let mut d = c.clone().cholesky().unwrap().solve(&r);
        let mut mu = 0.0;
        if u[0] + d[0] < -2.27 {
            let d0 = -2.27 - u[0];
            let c11 = c.view((1, 1), (n - 1, n - 1)).into_owned();
            let r1 = r.rows(1, n - 1) - c.view((1, 0), (n - 1, 1)) * d0;
            let d1 = c11.cholesky().unwrap().solve(&r1);
            d[0] = d0;
            d.rows_mut(1, n - 1).copy_from(&d1);
            mu = (&c * &d - &r)[0];
            assert!(mu > -1e-9 * r[0].abs().max(1.0), "tensile reaction {mu}");
        }
        u += &d;
        v = v_pred + &d * (gamma / (beta * dt));
        acc = a_pred + &d / (beta * dt * dt);
        out.push(BarState {
            u: u.iter().copied().collect(),
            v: v.iter().copied().collect(),
            mu,
        });
    }
    out
}

/// SDNV103 E's time list and scheme (one step of 9.75e-6 s, then steps of
/// 5e-8 s; Newmark β = 0.49, γ = 0.9) on an elastic column of AXIS QUAD4
/// (ν = 0, DX blocked: the exact solution is uniform in r, a 1D bar) whose
/// bottom closes the gap to a LIAISON_UNIL floor exactly at t = 0. Every
/// DEPL, VITE and the bottom REAC_NODA of every step equal the
/// independent reference `bar_on_floor_reference`. The reference shows
/// what E's A1 does: held in the step after the impact with the Newmark
/// velocity (1 − γ/β)(−V) = +189939 mm/s *upwards* (δ = 0 in
/// v = (1 − γ/β)v_n + γ/(βΔt)δ), released at the next step, back on the
/// floor some steps later — and whether it is back at 2.5e-7 depends on
/// the layer height alone: 30 layers (h = 1.08) is above the floor there,
/// 34 layers (h = 0.95) on it (docs/contact.md §9).
#[test]
fn sdnv103e_time_list_bounce_is_newmark_and_depends_on_the_layer_height() {
    let v0 = 227000.0;
    let mut times = vec![-1e-5];
    for k in 0..=15 {
        times.push(-2.5e-7 + k as f64 * 5e-8);
    }
    for (n2, on_floor_at_2_5e_7) in [(30, false), (34, true)] {
        let mut mesh = generate(&TaylorParams {
            kind: TaylorKind::Axis,
            n1: 1,
            n2,
            n3: 0,
            linear: true,
        })
        .unwrap();
        mesh.name = "MAIL".into();
        let vol = mesh.cell_groups["VOL"].clone();
        let nodes = mesh.nodes_of_cells(&vol);
        let bottom = mesh.nodes_of_cells(&mesh.cell_groups["SZZ"]);
        assert_eq!(bottom.len(), 2);
        let mo = model(&mesh, "AXIS", &vol);
        let mut st = study(
            mesh.clone(),
            mo,
            material(117000.0, 0.0, 8.93e-9, None),
            imposed(&nodes, Dof::Dx, 0.0),
            Some(velocity(mesh.nnodes(), &nodes, -v0)),
            times.clone(),
            None,
        );
        insert_function(&mut st, "CI", Function::constant(2.27, "TOUTRESU"));
        run(
            &mut st,
            "_F(GROUP_MA='SZZ', NOM_CMP='DY', COEF_MULT=CM1, COEF_IMPO=CI)",
            "SCHEMA='NEWMARK', BETA=0.49, GAMMA=0.9, FORMULATION='DEPLACEMENT'",
            "INCREMENT=_F(LIST_INST=L_INST)",
        )
        .unwrap();
        let r = result(&st, "RESU");
        assert_eq!(r.steps.len(), times.len());
        // Per radian, as the AXIS nodal forces.
        let reference = bar_on_floor_reference(n2, 3.2 * 3.2 / 2.0, v0, &times);
        let h = 32.4 / n2 as f64;
        for (s, st_ref) in reference.iter().enumerate() {
            let step = s + 1;
            for &i in &nodes {
                let layer = ((mesh.coords[i][1] - 2.27) / h).round() as usize;
                let (u, v) = (st_ref.u[layer], st_ref.v[layer]);
                let du = val(r, step, "DEPL", i, "DY") - u;
                let dv = val(r, step, "VITE", i, "DY") - v;
                assert!(
                    du.abs() < 1e-10 && dv.abs() < 1e-4,
                    "n2 {n2}, t = {:e}, node {}: DY {u} + {du:e}, VY {v} + {dv:e}",
                    times[step],
                    i + 1
                );
            }
            let reac: f64 = bottom
                .iter()
                .map(|&i| val(r, step, "REAC_NODA", i, "DY"))
                .sum();
            assert!(
                (reac - st_ref.mu).abs() < 1e-7 * 2e4,
                "n2 {n2}, t = {:e}: REAC_NODA {reac} vs {}",
                times[step],
                st_ref.mu
            );
        }
        // The mechanism, read on the reference: held at 5e-8 with the
        // Newmark velocity of a stopped node, released at 1e-7.
        let (held, released) = (&reference[6], &reference[7]);
        assert!(held.mu > 0.0 && held.u[0] == -2.27);
        assert!((held.v[0] - (1.0 - 0.9 / 0.49) * -v0).abs() < 1e-6 * v0);
        assert!(released.mu == 0.0 && released.u[0] > -2.27 + 1e-3);
        let at = &reference[10];
        assert_eq!(at.u[0] == -2.27, on_floor_at_2_5e_7, "n2 {n2}: {}", at.u[0]);
    }
}

/// LIAISON_UNIL produces no CONT_NOEU (as code_aster): asking for it is a
/// clear error pointing to REAC_NODA.
#[test]
fn no_cont_noeu_for_unilateral_conditions() {
    let (mut st, _, _) = single_node(1e-9, 8.93e-9, -1000.0, linspace(0.0, 1e-6, 1));
    insert_function(&mut st, "CI", Function::constant(0.0, "TOUTRESU"));
    run(
        &mut st,
        ONE_NODE,
        "SCHEMA='NEWMARK', BETA=0.25, GAMMA=0.5, FORMULATION='DEPLACEMENT'",
        "INCREMENT=_F(LIST_INST=L_INST)",
    )
    .unwrap();
    let text = "T = POST_RELEVE_T(ACTION=_F(INTITULE='C', GROUP_NO='A1', RESULTAT=RESU, NOM_CHAM='CONT_NOEU', TOUT_CMP='OUI', OPERATION='EXTRACTION'))";
    let full = format!(
        "{FUNCTIONS}\nUNIL = DEFI_CONTACT(MODELE=MO, FORMULATION='LIAISON_UNIL', ZONE=({ONE_NODE}))\nRESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, CONTACT=UNIL, COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=L_INST), SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))\n{text}"
    );
    let err = exec(
        &mut st,
        "POST_RELEVE_T",
        &args_of(&full, "POST_RELEVE_T", 0),
        "T",
    )
    .expect_err("CONT_NOEU must be refused");
    assert!(
        err.contains("LIAISON_UNIL") && err.contains("REAC_NODA"),
        "{err}"
    );
}

/// LIAISON_UNIL in explicit dynamics (an aster extension over code_aster's
/// MECANONLINE5_23, tests/explicit_unilateral.rs) needs the lumped mass,
/// which makes the nodes' links independent: without MASS_DIAG='OUI' it is
/// a clear error.
#[test]
fn explicit_schemes_need_the_lumped_mass() {
    let (mut st, _, _) = single_node(1e-9, 8.93e-9, -1000.0, linspace(0.0, 1e-6, 1));
    insert_function(&mut st, "CI", Function::constant(0.0, "TOUTRESU"));
    let err = run(
        &mut st,
        ONE_NODE,
        "SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'",
        "INCREMENT=_F(LIST_INST=L_INST)",
    )
    .expect_err("explicit scheme with LIAISON_UNIL and the consistent mass");
    assert!(
        err.contains("consistent mass") && err.contains("MASS_DIAG='OUI'"),
        "{err}"
    );
}

/// DEFI_FONCTION gives COEF_IMPO as a function of INST: the floor of the
/// spring test defined in the command language gives the node exactly on
/// it; a bad VALE (odd count, decreasing abscissas) is a clear error.
#[test]
fn defi_fonction_gives_an_inst_dependent_floor() {
    let text = "F1 = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0.5, 1., -0.5), PROL_GAUCHE='LINEAIRE', PROL_DROITE='LINEAIRE')
F2 = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0.5, 1.))
F3 = DEFI_FONCTION(NOM_PARA='X', VALE=(1., 0.5, 0., 1.))";
    let (mut st, a1, _) = single_node(1e5, 1e-15, 0.0, linspace(0.0, 2.0, 20));
    exec(
        &mut st,
        "DEFI_FONCTION",
        &args_of(text, "DEFI_FONCTION", 0),
        "F1",
    )
    .unwrap();
    let f = match st.concepts.data("F1") {
        Some(ConceptData::Function(f)) => (**f).clone(),
        _ => panic!("F1 is not a function"),
    };
    assert_eq!(f.eval(1.5).unwrap(), -1.0);
    insert_function(&mut st, "CI", f);
    run(
        &mut st,
        ONE_NODE,
        "SCHEMA='NEWMARK', BETA=0.25, GAMMA=0.5, FORMULATION='DEPLACEMENT'",
        "INCREMENT=_F(LIST_INST=L_INST)",
    )
    .unwrap();
    let r = result(&st, "RESU");
    let last = r.steps.len() - 1;
    assert!((val(r, last, "DEPL", a1, "DY") - 1.5).abs() < 1e-12);
    let e = exec(
        &mut st,
        "DEFI_FONCTION",
        &args_of(text, "DEFI_FONCTION", 1),
        "F2",
    )
    .expect_err("odd VALE");
    assert!(e.contains("even count"), "{e}");
    let e = exec(
        &mut st,
        "DEFI_FONCTION",
        &args_of(text, "DEFI_FONCTION", 2),
        "F3",
    )
    .expect_err("decreasing abscissas");
    assert!(e.contains("strictly increasing"), "{e}");
}

/// Definition errors are located and say what is wrong: lengths of
/// NOM_CMP and COEF_MULT (UNILATER_42), different ALGO_CONT (CONTACT3_4),
/// a COEF_MULT of X (code_aster evaluates it with INST only), a condition
/// on a component that DDL_IMPO imposes.
#[test]
fn definition_errors_are_clear() {
    let schema = "SCHEMA='NEWMARK', BETA=0.25, GAMMA=0.5, FORMULATION='DEPLACEMENT'";
    let inc = "INCREMENT=_F(LIST_INST=L_INST)";
    let cases: [(&str, &str); 4] = [
        (
            "_F(GROUP_NO='A1', NOM_CMP=('DX', 'DY'), COEF_MULT=CM1, COEF_IMPO=CI)",
            "same length",
        ),
        (
            "_F(GROUP_NO='A1', NOM_CMP='DY', COEF_MULT=CM1, COEF_IMPO=CI), _F(GROUP_NO='A1', NOM_CMP='DY', COEF_MULT=CM1, COEF_IMPO=CI, ALGO_CONT='PENALISATION', COEF_PENA=1.E6)",
            "same ALGO_CONT",
        ),
        (
            "_F(GROUP_NO='A1', NOM_CMP='DY', COEF_MULT=CI2, COEF_IMPO=CI)",
            "COEF_MULT is evaluated with the parameter INST only",
        ),
        (
            "_F(GROUP_NO='A1', NOM_CMP='DZ', COEF_MULT=CM1, COEF_IMPO=CI)",
            "none of NOM_CMP (DZ) is a degree of freedom of the model MO",
        ),
    ];
    for (zones, want) in cases {
        let (mut st, _, _) = single_node(1e-9, 8.93e-9, -1000.0, linspace(0.0, 1e-6, 1));
        insert_function(&mut st, "CI", Function::constant(0.0, "TOUTRESU"));
        let fx = Function::new("X", "TOUTRESU", vec![0.0, 1.0], vec![-1.0, -1.0]).unwrap();
        insert_function(&mut st, "CI2", fx);
        let e = run(&mut st, zones, schema, inc).expect_err(want);
        assert!(e.contains(want), "{want}: {e}");
    }
    // A link on a component imposed by DDL_IMPO (DX here) is accepted, as
    // code_aster does: the imposed value moves to the right-hand side and
    // the link, satisfied, stays inert.
    let (mut st, _, _) = single_node(1e-9, 8.93e-9, -1000.0, linspace(0.0, 1e-6, 1));
    insert_function(&mut st, "CI", Function::constant(0.0, "TOUTRESU"));
    run(
        &mut st,
        "_F(GROUP_NO='A1', NOM_CMP='DX', COEF_MULT=CM1, COEF_IMPO=CI)",
        schema,
        inc,
    )
    .unwrap();
}
