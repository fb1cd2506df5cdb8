//! The messages of one frame, built from a World: the same for an MCAP recording and the live view.

use crate::fluid::{drawn_region, fluid_arrows};
use crate::network::{ContactForce, collect_contact_forces};
use crate::quantities::{ParticleColours, mean_inscribed_radius};
use crate::recorder::{DEFAULT_FORCE_WIDTH_RADII, RecordOptions};
use crate::scene::{SceneStyle, contacts_update, fluid_update, particles_update, timestamp, walls_update};
use crate::stats::FrameStats;
use foxglove::schemas::SceneUpdate;
use gc2d_engine::{BodyKind, World};
use gc2d_geometry::{Aabb, Pose};

/// Layers are this many mean inscribed radii apart in z.
const LAYER_SPACING_RADII: f64 = 0.05;

/// The messages of one frame, in the topics' order.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Log time: simulated nanoseconds since t = 0.
    pub log_time: u64,
    /// `/particles`.
    pub particles: SceneUpdate,
    /// `/walls`: `Some` in the first frame and whenever a wall moved since the last frame that carried them (or in
    /// every frame, see [`FrameBuilder::walls_every_frame`]).
    pub walls: Option<SceneUpdate>,
    /// `/contacts`: the force network, when [`RecordOptions::force_network`] is on.
    pub contacts: Option<SceneUpdate>,
    /// `/fluid`: the fluid's velocity arrows, in every frame of a World with a fluid (the field may change in
    /// time); `None` without a fluid.
    pub fluid: Option<SceneUpdate>,
    /// `/stats`.
    pub stats: FrameStats,
}

/// Scales fixed at the first frame that has particles.
#[derive(Debug, Clone, Copy)]
struct Scales {
    force_line_max_width: f64,
    layer_spacing: f64,
}

/// Builds the frames of one run, keeping what must stay fixed from frame to frame (the drawing's length scales, the
/// walls last sent) and reusing its buffers.
#[derive(Debug, Clone)]
pub struct FrameBuilder {
    options: RecordOptions,
    scales: Option<Scales>,
    frames: u64,
    wall_poses: Vec<Pose>,
    forces: Vec<ContactForce>,
    colours: ParticleColours,
    walls_every_frame: bool,
    /// The region the fluid is drawn over, fixed by the first frame.
    fluid_region: Option<Aabb>,
}

impl FrameBuilder {
    /// A builder for frames that look as `options` say.
    pub fn new(options: RecordOptions) -> Self {
        Self {
            options,
            scales: None,
            frames: 0,
            wall_poses: Vec::new(),
            forces: Vec::new(),
            colours: ParticleColours::default(),
            walls_every_frame: false,
            fluid_region: None,
        }
    }

    /// Sends the walls in every frame, moved or not: for viewers that may join a running stream (the live view).
    pub fn walls_every_frame(mut self) -> Self {
        self.walls_every_frame = true;
        self
    }

    /// Frames built so far.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// The frame of `world` as it is now, at log time `log_time` (simulated nanoseconds).
    pub fn build(&mut self, world: &World, log_time: u64) -> Frame {
        let scales = self.scales(world);
        let walls_changed = self.walls_changed(world);
        let style =
            SceneStyle { timestamp: timestamp(log_time), layer_spacing: scales.map_or(0.0, |s| s.layer_spacing) };
        let max_force = collect_contact_forces(world, &mut self.forces);
        self.colours.update(world, self.options.colour_by, self.options.colour_range, &self.forces);
        let particles = particles_update(world, &self.colours.colours, &style);
        let walls = walls_changed.then(|| walls_update(world, &style));
        let contacts = self.options.force_network.then(|| {
            let width = scales.map_or(0.0, |s| s.force_line_max_width);
            contacts_update(world, &self.forces, max_force, width, &style)
        });
        let fluid = world.fluid().and_then(|_| {
            let region = *self.fluid_region.get_or_insert(drawn_region(world)?);
            fluid_arrows(world, region).map(|arrows| fluid_update(&arrows, &style))
        });
        let stats = FrameStats::of(world, &self.forces, max_force);
        self.frames += 1;
        Frame { log_time, particles, walls, contacts, fluid, stats }
    }

    /// The length scales of the drawing, fixed by the first frame with particles.
    fn scales(&mut self, world: &World) -> Option<Scales> {
        if self.scales.is_none() {
            let radius = mean_inscribed_radius(world);
            let width = self.options.force_line_max_width.or(radius.map(|r| DEFAULT_FORCE_WIDTH_RADII * r));
            if let (Some(radius), Some(width)) = (radius, width) {
                self.scales = Some(Scales { force_line_max_width: width, layer_spacing: LAYER_SPACING_RADII * radius });
            }
        }
        self.scales
    }

    /// True in the first frame and whenever a wall's pose differs from the one last written (then remembers it).
    fn walls_changed(&mut self, world: &World) -> bool {
        let bodies = world.bodies();
        let walls = (0..bodies.len()).filter(|&i| bodies.kind[i] == BodyKind::Wall).map(|i| bodies.pose[i]);
        let changed = self.walls_every_frame || self.frames == 0 || !walls.clone().eq(self.wall_poses.iter().copied());
        if changed {
            self.wall_poses.clear();
            self.wall_poses.extend(walls);
        }
        changed
    }
}
