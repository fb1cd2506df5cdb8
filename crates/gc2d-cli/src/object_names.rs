//! The scene's names of the World's bodies, for messages and tables: `walls[0]`, `particles[3]`, `blocks[1] #17`
//! (from the scene's build, `Scene::body_origins`) and, for particles inserted during the run, `sources[1] #17` or
//! `inlets[0] #4` (the source's or inlet's particle after 17 or 4 others, from the World's insertion log).

use gc2d_engine::{BodyId, Inserter, World};
use gc2d_scene::Scene;

/// The names of a scene's bodies.
#[derive(Debug, Clone, Default)]
pub struct ObjectNames {
    /// The scene entry of each body of the start, by body id.
    origins: Vec<String>,
}

impl ObjectNames {
    /// The names of `scene`'s bodies (builds the scene once more, naming each body); none where it cannot be built.
    pub fn of_scene(scene: &Scene) -> Self {
        Self { origins: scene.body_origins().unwrap_or_default() }
    }

    /// The names given by `origins`, the scene entries of the bodies of the start by id.
    pub fn from_origins(origins: Vec<String>) -> Self {
        Self { origins }
    }

    /// The scene's name of body `id` of `world`; `body <id>` for a body the scene does not name (added by hand).
    pub fn name(&self, world: &World, id: BodyId) -> String {
        if let Some(origin) = self.origins.get(id.index()) {
            return origin.clone();
        }
        match world.insertion(id) {
            Some(insertion) => match insertion.by {
                Inserter::Source(s) => format!("sources[{s}] #{}", insertion.ordinal),
                Inserter::Inlet(i) => format!("inlets[{i}] #{}", insertion.ordinal),
            },
            None => format!("body {}", id.0),
        }
    }
}
