//! Materials and the interaction table: which contact model acts between two bodies, by their materials.
//!
//! Every body, walls included, has a [`MaterialId`]. The engine does not know what a material is made of: the scene
//! crate resolves materials and the scene's interaction table (with its mixing rules for pairs the scene does not
//! list) into one [`ContactModel`] per material pair, and the narrowphase looks the model up per body pair.

use gc2d_contact::{ContactLaw, ContactLawError, PenetrationLaw, PenetrationLawError};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Index of a material in the World's interaction table; 0 is the material of bodies that were given none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default, Serialize, Deserialize)]
pub struct MaterialId(pub u16);

impl MaterialId {
    /// The index as a `usize`.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// The contact model of one material pair.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[allow(
    clippy::large_enum_variant,
    reason = "a table holds a handful of models and the narrowphase reads them by reference; a box would add a \
              pointer chase to every pair evaluation"
)]
pub enum ContactModel {
    /// gc2d's overlap-area law (reference §2.4–§2.11): F⊥ = E·A/l with damping, Cundall–Strack friction, cohesion.
    OverlapArea(ContactLaw),
    /// A penetration-depth law (linear spring or Hertz, with damping from D, e or e(v), friction and rolling
    /// resistance): the laws of the ball-mill and feed-pipe theses (docs/model.md, "Penetration laws").
    Penetration(PenetrationLaw),
}

impl From<ContactLaw> for ContactModel {
    fn from(law: ContactLaw) -> Self {
        ContactModel::OverlapArea(law)
    }
}

impl From<PenetrationLaw> for ContactModel {
    fn from(law: PenetrationLaw) -> Self {
        ContactModel::Penetration(law)
    }
}

/// A contact model's parameter out of range.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum ContactModelError {
    /// The overlap-area law's.
    #[error(transparent)]
    OverlapArea(#[from] ContactLawError),
    /// A penetration law's.
    #[error(transparent)]
    Penetration(#[from] PenetrationLawError),
}

impl ContactModel {
    /// Checks the model's parameters.
    pub fn validate(&self) -> Result<(), ContactModelError> {
        match self {
            ContactModel::OverlapArea(law) => Ok(law.validate()?),
            ContactModel::Penetration(law) => Ok(law.validate()?),
        }
    }

    /// The overlap-area law, if this is one.
    pub fn overlap_area(&self) -> Option<&ContactLaw> {
        match self {
            ContactModel::OverlapArea(law) => Some(law),
            ContactModel::Penetration(_) => None,
        }
    }
}

/// The contact model of every pair of materials: a symmetric table over `material_count` materials.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InteractionTable {
    material_count: usize,
    models: Vec<ContactModel>,
    /// `pair_model[a·n + b]` is the index into `models` of the pair (a, b); symmetric.
    pair_model: Vec<u16>,
}

/// Why an interaction table cannot be built.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum InteractionError {
    /// No materials, or more than a `u16` can number.
    #[error("an interaction table needs between 1 and 65,535 materials, got {0}")]
    MaterialCount(usize),
    /// A pair names a material beyond the table.
    #[error("material {material} is out of range: the table has {count} materials")]
    UnknownMaterial {
        /// The material index.
        material: u16,
        /// Materials in the table.
        count: usize,
    },
    /// A pair of materials has no model.
    #[error("materials {a} and {b} have no contact model")]
    MissingPair {
        /// First material.
        a: u16,
        /// Second material.
        b: u16,
    },
    /// A pair is given twice.
    #[error("materials {a} and {b} are given two contact models")]
    DuplicatePair {
        /// First material.
        a: u16,
        /// Second material.
        b: u16,
    },
    /// A model's parameters are out of range.
    #[error("contact model of materials {a} and {b}: {error}")]
    Model {
        /// First material.
        a: u16,
        /// Second material.
        b: u16,
        /// What is wrong.
        error: ContactModelError,
    },
}

/// One row of an interaction table: the model of materials `a` and `b` (in either order).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialPair {
    /// One material.
    pub a: MaterialId,
    /// The other material (may equal `a`).
    pub b: MaterialId,
    /// Their contact model.
    pub model: ContactModel,
}

impl InteractionTable {
    /// One material whose bodies all interact by `model`: the gc2d scenes, which have one law per scene.
    pub fn uniform(model: impl Into<ContactModel>) -> Self {
        Self { material_count: 1, models: vec![model.into()], pair_model: vec![0] }
    }

    /// A table over `material_count` materials from one row per unordered pair; every pair must be given once.
    pub fn new(material_count: usize, pairs: &[MaterialPair]) -> Result<Self, InteractionError> {
        if material_count == 0 || material_count > usize::from(u16::MAX) {
            return Err(InteractionError::MaterialCount(material_count));
        }
        let mut pair_model = vec![u16::MAX; material_count * material_count];
        let mut models = Vec::new();
        for pair in pairs {
            let (a, b) = (pair.a.index(), pair.b.index());
            for m in [pair.a, pair.b] {
                if m.index() >= material_count {
                    return Err(InteractionError::UnknownMaterial { material: m.0, count: material_count });
                }
            }
            if pair_model[a * material_count + b] != u16::MAX {
                return Err(InteractionError::DuplicatePair { a: pair.a.0, b: pair.b.0 });
            }
            pair.model.validate().map_err(|error| InteractionError::Model { a: pair.a.0, b: pair.b.0, error })?;
            let index = match models.iter().position(|m| *m == pair.model) {
                Some(index) => index,
                None => {
                    models.push(pair.model);
                    models.len() - 1
                }
            };
            pair_model[a * material_count + b] = index as u16;
            pair_model[b * material_count + a] = index as u16;
        }
        if let Some(missing) = pair_model.iter().position(|&m| m == u16::MAX) {
            let (a, b) = (missing / material_count, missing % material_count);
            return Err(InteractionError::MissingPair { a: a as u16, b: b as u16 });
        }
        Ok(Self { material_count, models, pair_model })
    }

    /// Number of materials.
    pub fn material_count(&self) -> usize {
        self.material_count
    }

    /// The distinct contact models of the table.
    pub fn models(&self) -> &[ContactModel] {
        &self.models
    }

    /// The contact model between materials `a` and `b`.
    #[inline]
    pub fn model(&self, a: MaterialId, b: MaterialId) -> &ContactModel {
        &self.models[usize::from(self.pair_model[a.index() * self.material_count + b.index()])]
    }

    /// For each material, the distinct models its bodies can meet: what bounds the time step of its particles.
    pub fn models_per_material(&self) -> Vec<Vec<&ContactModel>> {
        let n = self.material_count;
        (0..n)
            .map(|a| {
                let mut indices: Vec<u16> = self.pair_model[a * n..][..n].to_vec();
                indices.sort_unstable();
                indices.dedup();
                indices.into_iter().map(|m| &self.models[usize::from(m)]).collect()
            })
            .collect()
    }

    /// Checks every model's parameters and the table's shape (after loading a checkpoint).
    pub fn validate(&self) -> Result<(), InteractionError> {
        let n = self.material_count;
        if n == 0 || self.pair_model.len() != n * n {
            return Err(InteractionError::MaterialCount(n));
        }
        for a in 0..n {
            for b in 0..n {
                let m = usize::from(self.pair_model[a * n + b]);
                let (a16, b16) = (a as u16, b as u16);
                let model = self.models.get(m).ok_or(InteractionError::MissingPair { a: a16, b: b16 })?;
                model.validate().map_err(|error| InteractionError::Model { a: a16, b: b16, error })?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(mu: f64) -> ContactModel {
        let mut law = ContactLaw::elastic(1e7);
        law.friction = Some(gc2d_contact::CundallStrack { mu });
        ContactModel::OverlapArea(law)
    }

    #[test]
    fn a_table_is_symmetric_and_shares_equal_models() {
        let (m0, m1) = (MaterialId(0), MaterialId(1));
        let pairs = [
            MaterialPair { a: m0, b: m0, model: law(0.5) },
            MaterialPair { a: m1, b: m0, model: law(0.3) },
            MaterialPair { a: m1, b: m1, model: law(0.5) },
        ];
        let table = InteractionTable::new(2, &pairs).unwrap();
        assert_eq!(table.models().len(), 2);
        assert_eq!(*table.model(m0, m1), law(0.3));
        assert_eq!(*table.model(m1, m0), law(0.3));
        assert_eq!(*table.model(m1, m1), law(0.5));
        assert_eq!(table.models_per_material()[0].len(), 2);
        assert!(table.validate().is_ok());
    }

    #[test]
    fn missing_duplicate_and_unknown_pairs_are_refused() {
        let (m0, m1) = (MaterialId(0), MaterialId(1));
        let one = [MaterialPair { a: m0, b: m0, model: law(0.5) }];
        assert_eq!(InteractionTable::new(2, &one), Err(InteractionError::MissingPair { a: 0, b: 1 }));
        let twice = [one[0], MaterialPair { a: m0, b: m0, model: law(0.2) }];
        assert_eq!(InteractionTable::new(1, &twice), Err(InteractionError::DuplicatePair { a: 0, b: 0 }));
        let unknown = [MaterialPair { a: m0, b: m1, model: law(0.5) }];
        assert_eq!(
            InteractionTable::new(1, &unknown),
            Err(InteractionError::UnknownMaterial { material: 1, count: 1 })
        );
        let bad = [MaterialPair { a: m0, b: m0, model: law(-1.0) }];
        assert!(matches!(InteractionTable::new(1, &bad), Err(InteractionError::Model { .. })));
    }
}
