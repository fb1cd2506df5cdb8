//! The vocabulary of the gsi language (reference §9.3–§9.8): which commands each object has, how many parameters of
//! which type they take, their alternative spellings, and the "did you mean" search for misspelt ones.

/// The objects of a gsi file. GENERAL is implicit at the top; the others start with their name on a line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum ObjectKind {
    General,
    Display,
    Particle,
    Wall,
    GenerateBlock,
    DropSource,
}

impl ObjectKind {
    /// Every object, GENERAL first.
    pub const ALL: [ObjectKind; 6] = [
        ObjectKind::General,
        ObjectKind::Display,
        ObjectKind::Particle,
        ObjectKind::Wall,
        ObjectKind::GenerateBlock,
        ObjectKind::DropSource,
    ];

    /// The object's name as written in a gsi file.
    pub fn name(self) -> &'static str {
        match self {
            ObjectKind::General => "GENERAL",
            ObjectKind::Display => "DISPLAY",
            ObjectKind::Particle => "PARTICLE",
            ObjectKind::Wall => "WALL",
            ObjectKind::GenerateBlock => "GENERATE_BLOCK",
            ObjectKind::DropSource => "DROPSOURCE",
        }
    }

    /// The object named by `word` (any case), if any.
    pub fn from_name(word: &str) -> Option<ObjectKind> {
        Self::ALL.into_iter().find(|kind| kind.name().eq_ignore_ascii_case(word))
    }

    /// The commands of this object.
    pub fn commands(self) -> &'static [Command] {
        match self {
            ObjectKind::General => GENERAL,
            ObjectKind::Display => DISPLAY,
            ObjectKind::Particle => PARTICLE,
            ObjectKind::Wall => WALL,
            ObjectKind::GenerateBlock => GENERATE_BLOCK,
            ObjectKind::DropSource => DROPSOURCE,
        }
    }

    /// Whether the object has a CORNERS … END block.
    pub fn has_corners(self) -> bool {
        matches!(self, ObjectKind::Particle | ObjectKind::Wall)
    }

    /// The command of this object spelt `word` (any case, any accepted spelling).
    pub fn command(self, word: &str) -> Option<&'static Command> {
        self.commands().iter().find(|command| command.is_spelt(word))
    }
}

/// The parameters a command takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Arity {
    /// One float.
    Float,
    /// Two floats. gc2d set a missing second one to 0 (§9.2 rule 2); gc2d-rs refuses it, as a dropped number
    /// silently changes the experiment.
    FloatPair,
    /// One or two floats, for the commands documented with one (`G`, `SEED`, `DRAG_VELOCITY`): a missing second
    /// one keeps its documented meaning.
    FloatOneOrTwo,
    /// One non-negative integer.
    Whole,
    /// One or two integers of either sign (`SCREEN`, whose missing or zero height means "keep the aspect ratio").
    IntegerOneOrTwo,
    /// One word (an option name or a file name).
    Word,
    /// No parameter.
    Flag,
}

impl Arity {
    /// What the command expects, for error messages.
    pub fn describe(self) -> &'static str {
        match self {
            Arity::Float => "a number",
            Arity::FloatPair => "two numbers",
            Arity::FloatOneOrTwo => "one or two numbers",
            Arity::Whole => "a non-negative whole number",
            Arity::IntegerOneOrTwo => "one or two whole numbers",
            Arity::Word => "a word",
            Arity::Flag => "nothing",
        }
    }

    /// The least and the most values a command of this arity takes.
    pub fn counts(self) -> (usize, usize) {
        match self {
            Arity::Float | Arity::Whole | Arity::Word => (1, 1),
            Arity::FloatPair => (2, 2),
            Arity::FloatOneOrTwo | Arity::IntegerOneOrTwo => (1, 2),
            Arity::Flag => (0, 0),
        }
    }
}

/// One command: its canonical name, the other spellings gc2d's documentation uses, its parameters, what its values
/// are (for messages; empty for one value), and whether it is one of gc2d's System commands (checkpoint state, not
/// for users).
#[derive(Debug, Clone, Copy)]
pub(super) struct Command {
    pub name: &'static str,
    pub aliases: &'static [&'static str],
    pub arity: Arity,
    pub values: &'static str,
    pub system: bool,
}

impl Command {
    fn is_spelt(&self, word: &str) -> bool {
        self.name.eq_ignore_ascii_case(word) || self.aliases.iter().any(|alias| alias.eq_ignore_ascii_case(word))
    }

    fn spellings(&self) -> impl Iterator<Item = &'static str> {
        std::iter::once(self.name).chain(self.aliases.iter().copied())
    }

    /// The command with its values named `values` (e.g. `"x y, m"`).
    const fn of(mut self, values: &'static str) -> Command {
        self.values = values;
        self
    }
}

const fn user(name: &'static str, arity: Arity) -> Command {
    Command { name, aliases: &[], arity, values: "", system: false }
}

const fn alias(name: &'static str, aliases: &'static [&'static str], arity: Arity) -> Command {
    Command { name, aliases, arity, values: "", system: false }
}

const fn system(name: &'static str, arity: Arity) -> Command {
    Command { name, aliases: &[], arity, values: "", system: true }
}

/// The keyword that opens a corner list in PARTICLE and WALL.
pub(super) const CORNERS: &str = "CORNERS";
/// The keyword that closes a corner list.
pub(super) const END: &str = "END";
/// The keyword that ends the file.
pub(super) const END_OF_FILE: &str = "END_OF_FILE";

const GENERAL: &[Command] = &[
    user("DELTA_T", Arity::Float),
    user("TIME", Arity::FloatPair).of("start end, s"),
    user("MUE_STATISCH", Arity::Float),
    user("MUE_DYNAMISCH", Arity::Float),
    user("E_MODUL", Arity::Float),
    user("GAMMA", Arity::Float),
    user("COHESION", Arity::Float),
    user("STEPS_DATA", Arity::Whole),
    user("STEPS_CHECKPOINT", Arity::Whole),
    user("STEPS_SETUP", Arity::Whole),
    user("STEPS_DUMPLINE", Arity::Whole),
    user("SEED", Arity::FloatOneOrTwo).of("s1 s2"),
    user("BASENAME", Arity::Word),
    user("EMAIL", Arity::Word),
    system("NEXT_DATA_FILENUMBER", Arity::Whole),
    system("NEXT_SETUP_FILENUMBER", Arity::Whole),
    user("G", Arity::FloatOneOrTwo).of("g1 g2, m/s²"),
    user("G_TIME", Arity::FloatPair).of("t1 t2, s"),
    user("G_PARAMETER", Arity::FloatPair).of("p1 p2"),
    user("G_TYPE", Arity::Word),
    user("HEAT_TIME", Arity::FloatPair).of("t1 t2, s"),
    user("HEAT_AMPLITUDE", Arity::Float),
    alias("HEAT_FREQUENCE", &["HEAT_FREQUENCY"], Arity::Float),
    user("HEAT_SLOPE", Arity::Float),
];

const DISPLAY: &[Command] = &[
    user("X_RANGE", Arity::FloatPair).of("min max, m"),
    user("Y_RANGE", Arity::FloatPair).of("min max, m"),
    user("SCREEN", Arity::IntegerOneOrTwo).of("width height, pixels"),
    user("INTERVAL", Arity::Whole),
    user("MODUS", Arity::Whole),
];

const PARTICLE: &[Command] = &[
    user("COM", Arity::FloatPair).of("x y, m"),
    user("POSITION_ABSOLUT", Arity::Flag),
    user("VELOCITY", Arity::FloatPair).of("x y, m/s"),
    alias("ACCELERATION", &["VELOCITY_DOT"], Arity::FloatPair).of("x y, m/s²"),
    system("PC_TRANS3", Arity::FloatPair).of("x y, m/s³"),
    system("PC_TRANS4", Arity::FloatPair).of("x y, m/s⁴"),
    system("PC_TRANS5", Arity::FloatPair).of("x y, m/s⁵"),
    user("ANGLE", Arity::Float),
    user("OMEGA", Arity::Float),
    user("OMEGA_DOT", Arity::Float),
    system("PC_ROT3", Arity::Float),
    system("PC_ROT4", Arity::Float),
    system("PC_ROT5", Arity::Float),
    system("ID", Arity::Whole),
    user("DRAG_ANGLE", Arity::Float),
    user("DRAG_VELOCITY", Arity::FloatOneOrTwo).of("speed and an unused second value, m/s"),
    user("DRAG_K", Arity::Float),
    user("DRAG_TIME", Arity::FloatPair).of("start end, s"),
    user("DRAG_FIXING_POINT", Arity::FloatPair).of("x y, m"),
    user("DRAG_PULLING_POINT", Arity::FloatPair).of("x y, m"),
];

const WALL: &[Command] = &[
    user("OFFSET", Arity::FloatPair).of("x y, m"),
    user("ANGLE", Arity::Float),
    user("VELOCITY", Arity::FloatPair).of("x y, m/s"),
    system("ID", Arity::Whole),
    user("PISTON_ANGLE", Arity::Float),
    user("PISTON_FORCE", Arity::Float),
    user("PISTON_V_MAX", Arity::Float),
    user("VIB_ANGLE", Arity::Float),
    user("VIB_TIME", Arity::FloatPair).of("start end, s"),
    user("VIB_WIDTH", Arity::Float),
    alias("VIB_FREQUENCE", &["VIB_FREQUENCY"], Arity::Float),
    user("VIB_TYPE", Arity::Word),
];

/// The particle-shape commands shared by GENERATE_BLOCK and DROPSOURCE, with both spellings of the RANDOM_*
/// options (erratum E30).
macro_rules! shape_commands {
    () => {
        [
            user("PART_SIZE", Arity::FloatPair).of("l_x l_y, m"),
            user("PART_VAR_SIZE", Arity::Float),
            alias("RANDOM_SIZE", &["PART_RANDOM_SIZE"], Arity::Word),
            user("PART_NUM_CORNERS", Arity::Whole),
            user("PART_VAR_CORNERS", Arity::Whole),
            alias("RANDOM_NUM_CORNERS", &["PART_RANDOM_NUM_CORNERS"], Arity::Word),
            alias("PART_RANDOM_POS_CORNERS", &["RANDOM_POS_CORNERS"], Arity::Word),
            user("PART_ROT", Arity::Float),
            alias("RANDOM_ROT", &["PART_RANDOM_ROT"], Arity::Word),
        ]
    };
}

const GENERATE_BLOCK: &[Command] = &{
    let shape = shape_commands!();
    [
        user("X_RANGE", Arity::FloatPair).of("min max, m"),
        user("Y_RANGE", Arity::FloatPair).of("min max, m"),
        user("GRID_DISTANCE", Arity::FloatPair).of("Δx Δy, m"),
        user("GRID_TYPE", Arity::Word),
        user("ANGLE_RANGE", Arity::FloatPair).of("min max, rad"),
        user("VELOCITY_RANGE", Arity::FloatPair).of("min max, m/s"),
        shape[0],
        shape[1],
        shape[2],
        shape[3],
        shape[4],
        shape[5],
        shape[6],
        shape[7],
        shape[8],
    ]
};

const DROPSOURCE: &[Command] = &{
    let shape = shape_commands!();
    [
        user("POS", Arity::FloatPair).of("x y, m"),
        user("WIDTH", Arity::Float),
        user("TYPE", Arity::Word),
        user("TIME", Arity::FloatPair).of("start end, s"),
        user("DELTA_T", Arity::Float),
        shape[0],
        shape[1],
        shape[2],
        shape[3],
        shape[4],
        shape[5],
        shape[6],
        shape[7],
        shape[8],
    ]
};

/// The objects other than `current` that have a command spelt `word`.
pub(super) fn objects_with_command(word: &str, current: ObjectKind) -> Vec<&'static str> {
    ObjectKind::ALL
        .into_iter()
        .filter(|&kind| kind != current && kind.command(word).is_some())
        .map(ObjectKind::name)
        .collect()
}

/// The canonical spelling if `word` is any keyword of the language: a command of any object, an object name,
/// CORNERS, END or END_OF_FILE.
pub(super) fn is_any_keyword(word: &str) -> Option<&'static str> {
    let structural = [CORNERS, END, END_OF_FILE].into_iter().find(|k| k.eq_ignore_ascii_case(word));
    structural.or_else(|| object_or_command_name(word))
}

/// The canonical spelling if `word` is an object name or a command of any object (what line 2 starts with when
/// the identification line was forgotten).
pub(super) fn object_or_command_name(word: &str) -> Option<&'static str> {
    ObjectKind::from_name(word)
        .map(ObjectKind::name)
        .or_else(|| ObjectKind::ALL.into_iter().find_map(|kind| kind.command(word)).map(|command| command.name))
}

/// The closest word to `word` that is valid in `object` (its commands in every spelling, the object names, and the
/// structural keywords), if it is within a third of the word's length in edits (at least 2).
pub(super) fn suggestion(word: &str, object: ObjectKind) -> Option<&'static str> {
    let upper = word.to_ascii_uppercase();
    let mut candidates: Vec<&'static str> = object.commands().iter().flat_map(Command::spellings).collect();
    candidates.extend(ObjectKind::ALL.into_iter().skip(1).map(ObjectKind::name));
    candidates.push(END_OF_FILE);
    if object.has_corners() {
        candidates.push(CORNERS);
    }
    let limit = (upper.chars().count() / 3).max(2);
    candidates
        .into_iter()
        .map(|candidate| (edit_distance(&upper, candidate), candidate))
        .filter(|&(distance, _)| distance <= limit)
        .min_by_key(|&(distance, _)| distance)
        .map(|(_, candidate)| candidate)
}

/// Levenshtein distance (insertions, deletions and substitutions each cost 1), by characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    let mut current = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        current[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = previous[j] + usize::from(ca != cb);
            current[j + 1] = substitution.min(previous[j + 1] + 1).min(current[j] + 1);
        }
        std::mem::swap(&mut previous, &mut current);
    }
    previous[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_single_edits() {
        assert_eq!(edit_distance("WALL", "WALL"), 0);
        assert_eq!(edit_distance("WAL", "WALL"), 1);
        assert_eq!(edit_distance("DELTA_Y", "DELTA_T"), 1);
        assert_eq!(edit_distance("PISTON_FROCE", "PISTON_FORCE"), 2);
        assert_eq!(edit_distance("", "ABC"), 3);
    }

    #[test]
    fn both_spellings_name_the_same_command() {
        for kind in [ObjectKind::GenerateBlock, ObjectKind::DropSource] {
            for (a, b) in [
                ("Random_Num_Corners", "Part_Random_Num_Corners"),
                ("Random_Pos_Corners", "Part_Random_Pos_Corners"),
                ("random_size", "PART_RANDOM_SIZE"),
                ("Random_Rot", "Part_Random_Rot"),
            ] {
                let (a, b) = (kind.command(a).map(|c| c.name), kind.command(b).map(|c| c.name));
                assert!(a.is_some());
                assert_eq!(a, b);
            }
        }
    }

    #[test]
    fn no_object_lists_a_spelling_twice() {
        for kind in ObjectKind::ALL {
            let spellings: Vec<&str> = kind.commands().iter().flat_map(Command::spellings).collect();
            for (i, a) in spellings.iter().enumerate() {
                assert!(!spellings[i + 1..].contains(a), "{a} twice in {}", kind.name());
            }
        }
    }
}
