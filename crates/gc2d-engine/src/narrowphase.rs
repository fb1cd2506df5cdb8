//! The narrowphase: for one broadphase pair, the contact model of the two bodies' materials, the pair query of
//! their two shapes that model needs, then the model itself (reference §2.15). Polygon pairs under the overlap-area
//! law keep gc2d's path: closest features (warm-started; skipped while the pair keeps touching), then the overlap
//! and its contact chord. Each pair writes only its own record, so all pairs run in parallel; the engine adds the
//! forces to the bodies afterwards in pair order, which keeps results independent of threads.

use crate::bodies::{Bodies, BodyId, BodyKind};
use crate::clearance::Clearance;
use crate::heating::{area_contact_virial, penetration_virial};
use crate::interactions::{ContactModel, InteractionTable};
use crate::shape::ShapeKind;
use gc2d_contact::{
    AreaFormulation, BodyMotion, ContactLaw, ContactResponse, ContactState, EnergyTerms, PairProperties,
    PenetrationGeometry, PenetrationLaw, PenetrationResponse, PenetrationState, reciprocal_or_zero,
};
use gc2d_geometry::{
    AreaContact, DVec2, FeaturePair, ShapeView, area_contact, area_contact_with_centroid, closest_features,
    contact_geometry_from_exit, penetration,
};
use glam::Vec2;
use serde::{Deserialize, Serialize};

/// What a contact remembers between steps, of the kind its contact model keeps. A pair's model is fixed by its two
/// materials, so a pair keeps one kind for its life; a new pair starts as a not-touching overlap-area history, which
/// a penetration law reads as its own not-touching default.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum ContactHistory {
    /// The overlap-area law's history (old area, tangential spring, frozen l, m⊥, m∥).
    OverlapArea(ContactState),
    /// A penetration law's history (impact speed, episode damping, depth, springs).
    Penetration(PenetrationState),
}

impl Default for ContactHistory {
    fn default() -> Self {
        ContactHistory::OverlapArea(ContactState::default())
    }
}

impl ContactHistory {
    /// The overlap-area history, or the not-touching one.
    #[inline]
    pub fn overlap_area(&self) -> ContactState {
        match self {
            ContactHistory::OverlapArea(state) => *state,
            ContactHistory::Penetration(_) => ContactState::default(),
        }
    }

    /// The penetration history, or the not-touching one.
    #[inline]
    pub fn penetration(&self) -> PenetrationState {
        match self {
            ContactHistory::Penetration(state) => *state,
            ContactHistory::OverlapArea(_) => PenetrationState::default(),
        }
    }
}

/// Everything the World keeps about one pair of bodies whose boxes touch: the contact history and this step's result.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct PairContact {
    /// The warm start of the pair's next geometric query: the closest features of its last closest-feature query
    /// or, once a plain two-crossing overlap was found, the edges on which the outline of body `a` (of the particle,
    /// where `a` is a wall) left the other body's, from which the next overlap is looked for first (docs/model.md,
    /// "Contact geometry"). Saved in checkpoints, so a resumed run starts every query where the uninterrupted one
    /// would.
    pub warm_start: Option<FeaturePair>,
    /// The contact model's history.
    pub state: ContactHistory,
    /// Energy stored in the contact after this step (elastic, spring and cohesive), J: the contact term of the
    /// energy ledger, and the opening residual if the pair ends before it is evaluated again.
    pub stored_energy: f64,
    /// True when the bodies overlapped this step.
    pub touching: bool,
    /// Force on body `a` of the pair (body `b` receives the opposite), N.
    pub force_on_a: DVec2,
    /// Torque on body `a`, N·m.
    pub torque_on_a: f64,
    /// Torque on body `b`, N·m.
    pub torque_on_b: f64,
    /// Force application point, m: the midpoint of the contact chord (overlap-area law) or the contact point midway
    /// between the two surfaces (penetration laws).
    pub point: DVec2,
    /// Energy dissipated in the contact this step by damping and sliding, J (≥ 0): what the contact events add up
    /// per episode. The ledger's own terms are summed in the narrowphase pass and not kept per pair
    /// (`pair_sums.rs`).
    pub dissipated: f64,
    /// How far apart the pair is known to be, after the bodies' travel since its last closest-feature query
    /// (`Bodies::travel`): while it exceeds this step's travel of the two bodies, the pair is still apart and no
    /// query runs (docs/model.md, "Pairs apart by more than they moved"). [`Clearance::NONE`] while touching. Saved in
    /// checkpoints, so that a resumed run skips the same queries.
    pub clearance: Clearance,
    /// `force_on_a` of the two steps before this one, newest first: the history of the force-alternation
    /// diagnostic ([`World::force_alternation`](crate::World::force_alternation)). Not saved in checkpoints, so that
    /// the format stays; a resumed World measures the diagnostic again after two steps. Single precision: the
    /// diagnostic compares forces to a few digits (its threshold is 5 %), and 16 bytes fewer per pair.
    #[serde(skip)]
    pub earlier_forces: [Vec2; 2],
    /// Evaluations in a row, up to [`QUIET_EVALUATIONS`], in which the contact law found the pair apart and recorded
    /// its answer for a pair apart and not in contact before (no force, nothing stored or booked). From
    /// [`QUIET_EVALUATIONS`] on the record holds bit for bit what the next such evaluation would write, the force history
    /// included, so that evaluation leaves it alone and the step's sums skip it ([`Self::is_quiet`]): of the record
    /// only its last bytes (warm start, pass count, flags), one cache line with the pair's body ids, are read or
    /// written (docs/performance.md, "Quiet pairs"). Not saved in checkpoints: a resumed World counts again, and the
    /// record is the same either way.
    #[serde(skip)]
    pub quiet_evaluations: u8,
}

/// Evaluations of a pair apart after which its record no longer changes ([`PairContact::quiet_evaluations`]): the
/// first writes the law's answer, the next two shift the zero force through the force history.
pub const QUIET_EVALUATIONS: u8 = 3;

/// The part of a contact's [`EnergyTerms`] the energy ledger books, with the work of walls folded in (the
/// stored-energy changes are not needed, since the ledger reads the stored energy itself): what a pair's evaluation
/// returns for the step's sums.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct LedgerTerms {
    /// Dissipated by the normal damping, J (≥ 0).
    pub normal_damping: f64,
    /// Dissipated by the tangential damping, J (≥ 0).
    pub tangential_damping: f64,
    /// Dissipated by sliding, J (≥ 0).
    pub sliding: f64,
    /// Stored energy dropped when the contact opened this step, J (either sign).
    pub opening_residual: f64,
    /// Work done on the particle by a wall this step: its virtual surface velocity and its real motion, J.
    pub work_walls: f64,
}

impl LedgerTerms {
    /// The terms of a step whose contact reported `energy` and on which the wall's motion did `wall_work`.
    #[inline]
    pub fn of(energy: &EnergyTerms, wall_work: f64) -> Self {
        Self {
            normal_damping: energy.normal_damping,
            tangential_damping: energy.tangential_damping,
            sliding: energy.sliding,
            opening_residual: energy.opening_residual,
            work_walls: energy.surface_work + wall_work,
        }
    }

    /// Energy dissipated by damping and sliding, J (the sum [`EnergyTerms::dissipation`] gives).
    #[inline]
    pub fn dissipation(&self) -> f64 {
        self.normal_damping + self.tangential_damping + self.sliding
    }

    /// Adds `other` term by term.
    #[inline]
    pub fn add(&mut self, other: &LedgerTerms) {
        self.normal_damping += other.normal_damping;
        self.tangential_damping += other.tangential_damping;
        self.sliding += other.sliding;
        self.opening_residual += other.opening_residual;
        self.work_walls += other.work_walls;
    }
}

/// The overlap of polygons `i` and `j` this step, or `None` (the polygon–polygon path of the overlap-area law), with
/// the overlap centroid when `with_centroid` (the Winkler formulation; the others spend nothing on it), and the passes
/// its closest-feature walk needed (0 where none ran).
///
/// A pair that touched in the last step almost always still touches, so the overlap computation itself decides,
/// starting from the edges where the outlines crossed in the last step; a closest-feature query first would only
/// repeat its answer. A pair apart by more than its two bodies travelled since ([`PairContact::clearance`]) is still
/// apart, and nothing is read of its outlines. Every other pair (approaching, or just separated) asks the
/// warm-started closest-feature walk first (reference §4.3), which settles the common "apart" case without building
/// an overlap polygon, and keeps the warm start fresh for the step the pair comes into contact. Both kinds of query
/// read and write the one warm start: a crossing where `a` leaves `b` is what the closest-feature walk itself keeps
/// for an overlap.
///
/// Always inlined, as [`ContactLaw::evaluate`] is: the pair evaluation is compiled twice (with and without heating),
/// and the compiler then left this out of line (docs/performance.md, "Heating's work: what the others pay").
#[inline(always)]
fn polygon_overlap(
    bodies: &Bodies,
    i: BodyId,
    j: BodyId,
    with_centroid: bool,
    contact: &mut PairContact,
) -> (Option<AreaContact>, u16) {
    let (vertices_i, vertices_j) = (bodies.world_vertices_of(i), bodies.world_vertices_of(j));
    if contact.touching {
        if let Some(overlap) =
            contact_geometry_from_exit(vertices_i, vertices_j, with_centroid, &mut contact.warm_start)
        {
            return (Some(AreaContact::from(overlap)), 0);
        }
    } else {
        let clearance = contact.clearance.metres();
        let travel = f64::from(bodies.travel[i.index()]) + f64::from(bodies.travel[j.index()]);
        if clearance > travel {
            debug_assert!(
                closest_features(vertices_i, vertices_j, contact.warm_start).distance > 0.0,
                "a pair skipped as apart touches"
            );
            contact.clearance = Clearance::at_most(clearance - travel);
            return (None, 0);
        }
    }
    let separation = closest_features(vertices_i, vertices_j, contact.warm_start);
    contact.warm_start = Some(separation.features);
    let passes = u16::try_from(separation.passes).unwrap_or(u16::MAX);
    if separation.distance > 0.0 {
        contact.clearance = Clearance::at_most(separation.distance - rounding_allowance(bodies, i, j));
        return (None, passes);
    }
    contact.clearance = Clearance::NONE;
    if contact.touching {
        return (None, passes);
    }
    let overlap = contact_geometry_from_exit(vertices_i, vertices_j, with_centroid, &mut contact.warm_start);
    (overlap.map(AreaContact::from), passes)
}

/// What a distance between the world outlines of bodies `i` and `j` may be off by, m: their vertices are rounded
/// from the poses to a few units in the last place of the largest coordinate (centroid plus reach), at the step a
/// [`Clearance`] is measured as at any later one. 2⁻⁴⁰ of that largest coordinate is a thousand times more, and
/// still far below any gap a step closes.
fn rounding_allowance(bodies: &Bodies, i: BodyId, j: BodyId) -> f64 {
    let largest_coordinate = |id: BodyId| {
        let pose = &bodies.pose[id.index()];
        pose.position.abs().max_element() + bodies.reach[id.index()] * pose.scale
    };
    (largest_coordinate(i) + largest_coordinate(j)) * ROUNDING_ALLOWANCE
}

/// [`rounding_allowance`] per metre of the largest coordinate: 2⁻⁴⁰.
const ROUNDING_ALLOWANCE: f64 = 1.0 / (1u64 << 40) as f64;

/// What a pair's evaluation hands to the step's sums besides its record.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct PairEvaluation {
    /// The terms the energy ledger books.
    pub ledger: LedgerTerms,
    /// Passes the closest-feature walk needed (0 where none ran): the statistics count the queries that needed more
    /// than one.
    pub passes: u16,
    /// The pair's expansion virial where the World is heated (its normal force times the approach one unit of ln s
    /// gives, J; `heating.rs`), else 0.
    pub expansion_virial: f64,
}

/// What a pair evaluation reads: the body store as it is after the predictor.
pub(crate) struct PairContext<'a> {
    pub bodies: &'a Bodies,
    pub interactions: &'a InteractionTable,
    pub dt: f64,
}

impl PairContext<'_> {
    /// The contact law's view of body `id` at the predicted state.
    #[inline]
    pub fn motion(&self, id: BodyId) -> BodyMotion {
        let i = id.index();
        let b = self.bodies;
        BodyMotion {
            velocity: b.velocity[i],
            angular_velocity: b.angular_velocity[i],
            inv_mass: b.inverse_mass[i],
            inv_inertia: b.inverse_inertia[i],
            surface_velocity: b.surface_velocity_of(i),
        }
    }

    /// Evaluates the pair {a, b} (a < b) for this step, stores the result in `contact` and returns what the energy
    /// ledger books from it.
    ///
    /// When one body is a wall, the contact law sees the particle as body i; the stored result is always expressed
    /// for `a`, so that accumulation does not need to know. `HEATED`: whether the World is heated, so that a touching
    /// pair computes its expansion virial; a constant of the compiled code rather than a flag read per pair, since
    /// the test alone, with the code it guards, cost a World without heating 1.3 % more instructions a particle-step
    /// (docs/performance.md, "Heating's work: what the others pay").
    pub fn evaluate<const HEATED: bool>(&self, a: u32, b: u32, contact: &mut PairContact) -> PairEvaluation {
        let bodies = self.bodies;
        let wall_first = bodies.kind[a as usize] == BodyKind::Wall;
        let (i, j) = if wall_first { (BodyId(b), BodyId(a)) } else { (BodyId(a), BodyId(b)) };
        match self.interactions.model(bodies.material[i.index()], bodies.material[j.index()]) {
            ContactModel::OverlapArea(law) => self.evaluate_overlap_area::<HEATED>(law, i, j, wall_first, contact),
            ContactModel::Penetration(law) => self.evaluate_penetration::<HEATED>(law, i, j, wall_first, contact),
        }
    }

    /// The contact normal of the pair {a, b} (a < b) at the current poses, from j to i with i the particle when one
    /// body is a wall, by the query the pair's model uses; with i. `None` when the bodies do not overlap. For
    /// contact events (impact speeds at first touch), so it repeats a query the step already made, once per episode.
    pub fn contact_normal(&self, a: u32, b: u32) -> Option<(BodyId, BodyId, DVec2)> {
        let bodies = self.bodies;
        let wall_first = bodies.kind[a as usize] == BodyKind::Wall;
        let (i, j) = if wall_first { (BodyId(b), BodyId(a)) } else { (BodyId(a), BodyId(b)) };
        let (view_i, view_j) = (bodies.shape_view(i), bodies.shape_view(j));
        let normal = match self.interactions.model(bodies.material[i.index()], bodies.material[j.index()]) {
            ContactModel::OverlapArea(_) => area_contact(view_i, view_j).map(|c| c.normal),
            ContactModel::Penetration(_) => penetration(view_i, view_j).map(|p| p.normal),
        };
        normal.map(|n| (i, j, n))
    }

    /// How deep the pair {a, b} overlaps after its last evaluation: for the overlap-area law the overlap area as a
    /// fraction of the smaller particle's area, for penetration laws the depth as a fraction of the smaller
    /// particle's diameter; 0 when it does not touch. Read from the contact's history (the law keeps the area or
    /// depth it saw) rather than kept in every pair record: 8 bytes per pair (docs/performance.md, "Memory per
    /// particle"). An overlap the overlap-area law refused (zero characteristic length, docs/model.md "Overlap
    /// fraction") reads 0, as the law saw it.
    pub fn overlap_fraction(&self, a: u32, b: u32, contact: &PairContact) -> f64 {
        if !contact.touching {
            return 0.0;
        }
        let (a, b) = (BodyId(a), BodyId(b));
        match contact.state {
            ContactHistory::OverlapArea(state) => state.previous_area / self.smaller_particle_area(a, b),
            ContactHistory::Penetration(state) => state.previous_depth / (2.0 * self.smaller_radius(a, b)),
        }
    }

    /// A penetration law for the pair (i, j), i the particle when one body is a wall.
    fn evaluate_penetration<const HEATED: bool>(
        &self,
        law: &PenetrationLaw,
        i: BodyId,
        j: BodyId,
        wall_first: bool,
        contact: &mut PairContact,
    ) -> PairEvaluation {
        let bodies = self.bodies;
        let found = penetration(bodies.shape_view(i), bodies.shape_view(j));
        if found.is_none() && contact.is_quiet() {
            return PairEvaluation::default();
        }
        let (position_i, position_j) = (bodies.pose[i.index()].position, bodies.pose[j.index()].position);
        let geometry = found.map_or(PenetrationGeometry::SEPARATED, |p| PenetrationGeometry {
            depth: p.depth,
            normal: p.normal,
            arm_i: p.point - position_i,
            arm_j: p.point - position_j,
        });
        let previous = contact.state.penetration();
        // A pair apart now that was not touching before gets the law's answer for it (no force, nothing stored or
        // booked) without reading the bodies' velocities, as in `evaluate_overlap_area`.
        let (response, stored_energy, wall_work, expansion_virial) = if found.is_none() && !previous.is_touching() {
            contact.count_evaluation(true);
            (PenetrationResponse::default(), 0.0, 0.0, 0.0)
        } else {
            contact.count_evaluation(false);
            let (motion_i, motion_j) = (self.motion(i), self.motion(j));
            let radius_i = bodies.contact_radius(i.index());
            let surface_radius_j = match bodies.shape_view(j) {
                ShapeView::Disk { radius, .. } if bodies.kind[j.index()] == BodyKind::Particle => radius,
                ShapeView::Polygon(_) if bodies.kind[j.index()] == BodyKind::Particle => {
                    bodies.contact_radius(j.index())
                }
                _ => found.map_or(f64::INFINITY, |p| p.surface_radius_j),
            };
            let properties = pair_properties(radius_i, &motion_i, surface_radius_j, &motion_j, &geometry);
            let response = law.evaluate(&geometry, &properties, &motion_i, &motion_j, &previous, self.dt);
            let stored_energy = law.stored_energy(&properties, &response.state);
            let expansion_virial =
                if HEATED { self.penetration_expansion(law, j, &geometry, &properties, radius_i) } else { 0.0 };
            let wall_work = wall_work(&motion_j, geometry.arm_j, response.force_on_i, self.dt);
            (response, stored_energy, wall_work, expansion_virial)
        };
        contact.state = ContactHistory::Penetration(response.state);
        contact.stored_energy = stored_energy;
        let energy = LedgerTerms::of(&response.energy, wall_work);
        contact.dissipated = energy.dissipation();
        contact.touching = geometry.is_touching();
        contact.point = if contact.touching { position_i + geometry.arm_i } else { DVec2::ZERO };
        contact.record_force(wall_first, response.force_on_i, response.torque_on_i, response.torque_on_j);
        PairEvaluation { ledger: energy, passes: 0, expansion_virial }
    }

    /// The overlap-area law for the pair (i, j), i the particle when one body is a wall.
    fn evaluate_overlap_area<const HEATED: bool>(
        &self,
        law: &ContactLaw,
        i: BodyId,
        j: BodyId,
        wall_first: bool,
        contact: &mut PairContact,
    ) -> PairEvaluation {
        let bodies = self.bodies;
        let both_polygons =
            bodies.shape[i.index()] == ShapeKind::Polygon && bodies.shape[j.index()] == ShapeKind::Polygon;
        let with_centroid = law.elastic.formulation == AreaFormulation::Winkler;
        let (overlap, passes) = if both_polygons {
            polygon_overlap(bodies, i, j, with_centroid, contact)
        } else if with_centroid {
            (area_contact_with_centroid(bodies.shape_view(i), bodies.shape_view(j)), 0)
        } else {
            (area_contact(bodies.shape_view(i), bodies.shape_view(j)), 0)
        };
        if overlap.is_none() && contact.is_quiet() {
            return PairEvaluation { passes, ..PairEvaluation::default() };
        }
        let (position_i, position_j) = (bodies.pose[i.index()].position, bodies.pose[j.index()].position);
        let geometry = overlap.map_or(gc2d_contact::ContactGeometry::SEPARATED, |g| gc2d_contact::ContactGeometry {
            area: g.area,
            normal: g.normal,
            chord_length: g.chord_length,
            arm_i: g.point - position_i,
            arm_j: g.point - position_j,
            centroid_offset: g.centroid.map_or(0.0, |centroid| (centroid - g.point).dot(g.normal.perp())),
            rocking: bodies.shape[i.index()] != ShapeKind::Disk && bodies.shape[j.index()] != ShapeKind::Disk,
        });
        let previous = contact.state.overlap_area();
        // What the pair keeps of a response. Each branch below passes its response by reference: moving the
        // 176-byte struct out of the branch made the compiler copy it with a memcpy call, 4 % of a dense pile's
        // step (docs/performance.md, "Profile of a step").
        let record = |contact: &mut PairContact, response: &ContactResponse, wall_work: f64| {
            contact.state = ContactHistory::OverlapArea(response.state);
            contact.stored_energy = law.stored_energy(&response.state);
            let energy = LedgerTerms::of(&response.energy, wall_work);
            contact.dissipated = energy.dissipation();
            contact.touching = overlap.is_some();
            contact.point = overlap.map_or(DVec2::ZERO, |g| g.point);
            contact.record_force(wall_first, response.force_on_i, response.torque_on_i, response.torque_on_j);
            energy
        };
        // A pair apart now that was not in contact before (no contact constants) gets the law's answer for it, no
        // force and nothing to book, without reading the bodies' velocities: most box pairs of a pile are such
        // pairs (docs/performance.md, "Pairs apart skip the law"). Once its record holds that answer in full (a quiet
        // pair), writing it again would change no bit, so it is left alone.
        if overlap.is_none() && previous.constants.is_none() {
            contact.count_evaluation(true);
            let ledger = record(contact, &ContactResponse::default(), 0.0);
            PairEvaluation { ledger, passes, expansion_virial: 0.0 }
        } else {
            contact.count_evaluation(false);
            let (motion_i, motion_j) = (self.motion(i), self.motion(j));
            let response = law.evaluate(&geometry, &motion_i, &motion_j, &previous, self.dt);
            let expansion_virial =
                if HEATED { area_contact_virial(response.normal_force, &geometry, self.grows(j)) } else { 0.0 };
            let ledger = record(contact, &response, wall_work(&motion_j, geometry.arm_j, response.force_on_i, self.dt));
            PairEvaluation { ledger, passes, expansion_virial }
        }
    }

    /// The expansion virial of a penetration contact under `law` ([`penetration_virial`]), with the growth of its
    /// stored energy as the effective radius R* grows at a fixed depth (a Hertz spring stiffens with √R*), for heated
    /// Worlds only. `radius_i` is particle i's contact radius; R* grows with s where both bodies grow, and by
    /// R*/R_i per unit of ln s where j is a wall, whose radius stays.
    #[inline]
    fn penetration_expansion(
        &self,
        law: &PenetrationLaw,
        j: BodyId,
        geometry: &PenetrationGeometry,
        properties: &PairProperties,
        radius_i: f64,
    ) -> f64 {
        let (depth, radius, j_grows) = (geometry.depth, properties.effective_radius, self.grows(j));
        let radius_growth = if j_grows { 1.0 } else { radius / radius_i };
        let stiffening = law.normal.energy_radius_sensitivity(depth, radius) * radius_growth;
        penetration_virial(law.normal.force(depth, radius), geometry, j_grows) + stiffening
    }

    /// Whether body `id` grows with heating: a particle does, a wall does not.
    #[inline]
    fn grows(&self, id: BodyId) -> bool {
        self.bodies.kind[id.index()] == BodyKind::Particle
    }

    /// Area of the smaller particle of the pair at its current scale (walls do not count).
    fn smaller_particle_area(&self, i: BodyId, j: BodyId) -> f64 {
        self.bodies.overlap_reference_area(i.index()).min(self.bodies.overlap_reference_area(j.index()))
    }

    /// Contact radius of the smaller particle of the pair at its current scale (walls do not count), m.
    fn smaller_radius(&self, i: BodyId, j: BodyId) -> f64 {
        let radius = |id: BodyId| match self.bodies.kind[id.index()] {
            BodyKind::Particle => self.bodies.contact_radius(id.index()),
            BodyKind::Wall => f64::INFINITY,
        };
        radius(i).min(radius(j))
    }
}

impl PairContact {
    /// Whether the record holds, bit for bit, what an evaluation that finds the pair apart would write
    /// ([`Self::quiet_evaluations`]): no force now or in the force history, nothing stored, nothing dissipated.
    #[inline]
    pub fn is_quiet(&self) -> bool {
        self.quiet_evaluations >= QUIET_EVALUATIONS
    }

    /// Counts an evaluation in [`Self::quiet_evaluations`]: one more (up to [`QUIET_EVALUATIONS`]) where the law
    /// `answered_apart` (the pair apart and not in contact before: no force, nothing stored or booked), else none.
    #[inline]
    fn count_evaluation(&mut self, answered_apart: bool) {
        self.quiet_evaluations = if answered_apart { (self.quiet_evaluations + 1).min(QUIET_EVALUATIONS) } else { 0 };
    }

    /// Stores this step's force and torques, expressed for body `a` of the pair (the law computed them for i, which
    /// is `b` when `a` is a wall), and shifts the force history of the chatter diagnostic.
    #[inline]
    fn record_force(&mut self, wall_first: bool, force_on_i: DVec2, torque_on_i: f64, torque_on_j: f64) {
        let (sign, torque_a, torque_b) =
            if wall_first { (-1.0, torque_on_j, torque_on_i) } else { (1.0, torque_on_i, torque_on_j) };
        self.earlier_forces = [self.force_on_a.as_vec2(), self.earlier_forces[0]];
        self.force_on_a = sign * force_on_i;
        self.torque_on_a = torque_a;
        self.torque_on_b = torque_b;
    }
}

/// Work the real motion of body j, if it is a wall, does on particle i over the step through the force `force_on_i`
/// at `arm_j` from the wall's reference point, J; 0 when j is a particle (its work is in the kinetic energy).
#[inline]
fn wall_work(motion_j: &BodyMotion, arm_j: DVec2, force_on_i: DVec2, dt: f64) -> f64 {
    if motion_j.inv_mass == 0.0 {
        let wall_point_velocity = motion_j.velocity + motion_j.angular_velocity * arm_j.perp();
        force_on_i.dot(wall_point_velocity) * dt
    } else {
        0.0
    }
}

/// The pair properties of a penetration contact between particle i of contact radius `radius_i` and body j whose
/// outline has curvature radius `radius_j` at the contact (positive convex, negative concave, infinite flat):
/// R* = 1/(1/R_i + 1/R_j) (a concave chamber wall makes R* larger than R_i), the masses as for two disks with
/// the actual lever arms of the contact point.
fn pair_properties(
    radius_i: f64,
    motion_i: &BodyMotion,
    radius_j: f64,
    motion_j: &BodyMotion,
    geometry: &PenetrationGeometry,
) -> PairProperties {
    let curvature_j = if radius_j.is_finite() && radius_j != 0.0 { 1.0 / radius_j } else { 0.0 };
    let rotational = |arm: DVec2, body: &BodyMotion| arm.length_squared() * body.inv_inertia;
    let inv_mass = motion_i.inv_mass + motion_j.inv_mass;
    PairProperties {
        effective_radius: reciprocal_or_zero(1.0 / radius_i + curvature_j),
        effective_mass: reciprocal_or_zero(inv_mass),
        tangential_mass: reciprocal_or_zero(
            inv_mass + rotational(geometry.arm_i, motion_i) + rotational(geometry.arm_j, motion_j),
        ),
        rolling_inertia: reciprocal_or_zero(motion_i.inv_inertia + motion_j.inv_inertia),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gc2d_geometry::{Pose, square};

    /// The record lives in every broadphase pair and is most of a World's memory (docs/performance.md, "Memory per
    /// particle"): 264 bytes with a warm start of machine-word feature indices, 240 with byte indices and a
    /// two-byte pass count, 208 with the ledger's terms alone instead of all energy terms and the wall work, 192
    /// with the chatter watch's history in single precision, 160 with the ledger's terms summed in the narrowphase
    /// pass (`pair_sums.rs`) and only the dissipation kept, 152 with the overlap fraction read from the history
    /// ([`PairContext::overlap_fraction`]); the clearance took the two bytes of the walk's pass count.
    #[test]
    fn pair_record_is_at_most_152_bytes() {
        assert!(std::mem::size_of::<PairContact>() <= 152, "{} bytes", std::mem::size_of::<PairContact>());
    }

    /// Two unit squares, the second `gap` above the first (negative: overlapping).
    fn stacked(gap: f64) -> Bodies {
        let mut bodies = Bodies::default();
        let shape = square(1.0).unwrap();
        for y in [0.0, 1.0 + gap] {
            bodies.push(BodyKind::Particle, &(&shape).into(), Pose::new(DVec2::new(0.0, y), 0.0), 1.0, 1.0 / 6.0);
        }
        let mut broadphase = crate::broadphase::SortAndSweep::<()>::new();
        bodies.update_world_vertices(broadphase.box_writer(bodies.len()));
        bodies
    }

    /// The closest-feature query runs for pairs apart or just meeting, and is skipped while a pair keeps touching:
    /// then the overlap alone decides (`passes` = 0), with the same geometry the query would have led to.
    #[test]
    fn a_touching_pair_skips_the_closest_feature_query() {
        let law = InteractionTable::uniform(ContactLaw::elastic(1e7));
        let mut contact = PairContact::default();
        let apart = stacked(0.1);
        let evaluation =
            PairContext { bodies: &apart, interactions: &law, dt: 1e-6 }.evaluate::<false>(0, 1, &mut contact);
        assert!(!contact.touching);
        assert!(evaluation.passes >= 1 && contact.warm_start.is_some());

        let overlapping = stacked(-0.01);
        let evaluation =
            PairContext { bodies: &overlapping, interactions: &law, dt: 1e-6 }.evaluate::<false>(0, 1, &mut contact);
        assert!(contact.touching && evaluation.passes >= 1);
        let first_force = contact.force_on_a;

        let evaluation =
            PairContext { bodies: &overlapping, interactions: &law, dt: 1e-6 }.evaluate::<false>(0, 1, &mut contact);
        assert!(contact.touching);
        assert_eq!(evaluation.passes, 0);
        assert_eq!(contact.force_on_a, first_force, "same overlap, same elastic force");
        assert!(contact.point.x == 0.0 && (0.49..=0.5).contains(&contact.point.y), "{:?}", contact.point);
        let context = PairContext { bodies: &overlapping, interactions: &law, dt: 1e-6 };
        assert!((context.overlap_fraction(0, 1, &contact) - 0.01).abs() < 1e-12);

        let evaluation =
            PairContext { bodies: &apart, interactions: &law, dt: 1e-6 }.evaluate::<false>(0, 1, &mut contact);
        assert!(!contact.touching && evaluation.passes >= 1, "a pair that separated asks the query again");
        assert_eq!(contact.force_on_a, DVec2::ZERO);
    }

    /// A pair apart by more than its two bodies travelled since its last query skips the query and keeps the rest
    /// of its clearance; once the travel reaches the clearance, it asks again.
    #[test]
    fn a_pair_apart_by_more_than_its_travel_skips_the_query() {
        let law = InteractionTable::uniform(ContactLaw::elastic(1e7));
        let mut bodies = stacked(0.1);
        let mut contact = PairContact::default();
        let evaluate = |bodies: &Bodies, contact: &mut PairContact| {
            PairContext { bodies, interactions: &law, dt: 1e-6 }.evaluate::<false>(0, 1, contact).passes
        };
        assert!(evaluate(&bodies, &mut contact) >= 1, "never stepped: the travel is unknown");
        let clearance = contact.clearance.metres();
        assert!((0.1 * (1.0 - 1.0 / 128.0)..=0.1).contains(&clearance), "{clearance}");

        bodies.travel = vec![0.01, 0.02];
        assert_eq!(evaluate(&bodies, &mut contact), 0);
        let left = contact.clearance.metres();
        assert!(left <= clearance - 0.03 && left >= (clearance - 0.03) * (1.0 - 1.0 / 128.0), "{left}");

        bodies.travel = vec![f32::from_bits((left as f32).to_bits() + 1), 0.0];
        assert!(evaluate(&bodies, &mut contact) >= 1, "travel as large as the clearance: ask again");
        assert!(!contact.touching && contact.clearance.metres() > 0.09);
    }

    proptest::proptest! {
        /// A square turning and sliding towards another in random steps, each step's travel bounded from its poses
        /// as the integrator bounds it: whether the pair touches, and its force, are at every step what a pair record
        /// without history finds.
        #[test]
        fn skipping_queries_never_misses_a_contact(
            moves in proptest::collection::vec((-0.02f64..0.01, -0.01f64..0.01, -0.05f64..0.05), 1..120),
        ) {
            let law = InteractionTable::uniform(ContactLaw::elastic(1e7));
            let mut bodies = stacked(0.3);
            bodies.travel = vec![0.0, f32::INFINITY];
            let mut contact = PairContact::default();
            for (dy, dx, turn) in moves {
                let before = bodies.pose[1];
                let after = Pose { position: before.position + DVec2::new(dx, dy), angle: before.angle + turn, ..before };
                bodies.pose[1] = after;
                bodies.travel[1] = crate::bodies::travel_bound(&before, &after, bodies.reach[1]);
                let mut broadphase = crate::broadphase::SortAndSweep::<()>::new();
                bodies.update_world_vertices(broadphase.box_writer(bodies.len()));
                let context = PairContext { bodies: &bodies, interactions: &law, dt: 1e-6 };
                context.evaluate::<false>(0, 1, &mut contact);
                let mut fresh = PairContact::default();
                context.evaluate::<false>(0, 1, &mut fresh);
                proptest::prop_assert_eq!(contact.touching, fresh.touching);
                if !contact.touching {
                    proptest::prop_assert_eq!(contact.force_on_a, DVec2::ZERO);
                }
            }
        }
    }

    /// A pair that stays apart after a contact (a wall first, so the zero force is recorded as −0.0) becomes quiet
    /// after [`QUIET_EVALUATIONS`] evaluations, and from then on the evaluation that leaves the record alone ends
    /// with the same record, bit for bit, and returns the same terms as the full one; it turns loud again on touching.
    #[test]
    fn a_quiet_pair_keeps_the_record_a_full_evaluation_writes() {
        let hertz = gc2d_contact::NormalSpring::Hertz { effective_modulus_pa: 1e9 };
        let damped = PenetrationLaw {
            damping: Some(gc2d_contact::PenetrationDamping::Restitution(0.8)),
            ..PenetrationLaw::elastic(hertz)
        };
        for law in [InteractionTable::uniform(ContactLaw::elastic(1e7)), InteractionTable::uniform(damped)] {
            a_quiet_pair_keeps_the_record_under(&law);
        }
    }

    /// [`a_quiet_pair_keeps_the_record_a_full_evaluation_writes`] under the contact model of `law`.
    fn a_quiet_pair_keeps_the_record_under(law: &InteractionTable) {
        let (mut apart, mut overlapping) = (stacked(0.1), stacked(-0.01));
        for bodies in [&mut apart, &mut overlapping] {
            bodies.kind[0] = BodyKind::Wall;
        }
        let evaluate = |bodies: &Bodies, contact: &mut PairContact| {
            PairContext { bodies, interactions: law, dt: 1e-6 }.evaluate::<false>(0, 1, contact)
        };
        let bits = |contact: &PairContact| format!("{:?}", (contact.force_on_a.to_array().map(f64::to_bits), contact));
        let mut contact = PairContact::default();
        evaluate(&overlapping, &mut contact);
        evaluate(&overlapping, &mut contact);
        assert!(contact.touching && contact.earlier_forces[0] != glam::Vec2::ZERO);
        // The first evaluation apart still has the contact's constants and goes through the law; the quiet count
        // starts with the second.
        for evaluation in 1..=7_u8 {
            let mut full = contact;
            full.quiet_evaluations = 0;
            let full_terms = evaluate(&apart, &mut full);
            let terms = evaluate(&apart, &mut contact);
            assert_eq!(contact.quiet_evaluations, (evaluation - 1).min(QUIET_EVALUATIONS), "evaluation {evaluation}");
            assert_eq!(contact.is_quiet(), evaluation > QUIET_EVALUATIONS);
            full.quiet_evaluations = contact.quiet_evaluations;
            assert_eq!(bits(&contact), bits(&full), "evaluation {evaluation}");
            assert_eq!(terms, full_terms, "evaluation {evaluation}");
        }
        assert_eq!(contact.force_on_a.x.to_bits(), (-0.0_f64).to_bits(), "the wall's zero force is −0.0");
        evaluate(&overlapping, &mut contact);
        assert!(contact.touching && !contact.is_quiet());

        // A record that starts the count with a force now and two before (as after a law that still pulls on a pair
        // apart): only the third evaluation apart has shifted them all out.
        let mut contact = PairContact {
            force_on_a: DVec2::new(1.0, 0.0),
            earlier_forces: [glam::Vec2::new(2.0, 0.0), glam::Vec2::new(3.0, 0.0)],
            ..PairContact::default()
        };
        for evaluation in 1..=5_u8 {
            let mut full = contact;
            full.quiet_evaluations = 0;
            evaluate(&apart, &mut full);
            evaluate(&apart, &mut contact);
            full.quiet_evaluations = contact.quiet_evaluations;
            assert_eq!(bits(&contact), bits(&full), "with a history, evaluation {evaluation}");
        }
        assert!(contact.is_quiet() && contact.earlier_forces == [glam::Vec2::ZERO; 2]);
    }
}
