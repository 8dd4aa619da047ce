//! Saving a world and restoring it: [`World::save_state`] and [`World::load_state`].
//!
//! A state holds the world twice. Its *exact* part is everything the next steps read (bodies,
//! shapes, joints, the broad phase's tree, the contact cache with its warm-start impulses,
//! islands and sleep timers, settings, and the solver's buffers), so a world restored from it by
//! the build that wrote it steps bit for bit as the saved one would have. Its *portable
//! snapshot* is the world in frozen record types of its own (`state/portable.rs`), which every
//! later build reads.
//!
//! # Compatibility rule
//!
//! - The build that wrote a state (the same engine sources: the fingerprint says so) restores
//!   its exact part: bit-exact continuation.
//! - Any other build rebuilds the world from the portable snapshot. Kept: the settings; every
//!   body with its shape, pose, velocities, mass, centre of mass and inertia (as saved, not
//!   recomputed), material, damping, constant and applied forces, locked axes, sensor flag,
//!   groups, contact force threshold, user data, kinematic target, path and path clock, contact
//!   rules (one-way direction, surface velocity: since snapshot version 2), its triangle mesh's
//!   materials (since snapshot version 3), and its
//!   sleep (sleeping bodies stay asleep in their groups); every joint with its description, its
//!   frames in each body, broken flag, last force and revolute turn count (its spring's
//!   reference, armature and generic axes since snapshot version 4); ignored pairs; every
//!   handle (slots, generations and the world's identity), stale ones staying stale; every
//!   coupling with its description and rest length (since snapshot version 5). Not kept:
//!   contacts and warm-start impulses (contacts, joints and couplings start cold: the next step makes them again, so
//!   the steps after a load differ slightly from the exact continuation's, and contact and
//!   sensor start events are reported again), the broad phase's tree and solver buffers (rebuilt).
//! - Every later build reads every earlier snapshot version: a build that changes the records
//!   adds a version and converts the earlier ones to it. A snapshot of a version newer than the
//!   reading build knows is [`StateError::OtherBuild`]. States of format version 1 (exact part
//!   only) are [`StateError::OtherVersion`].
//!
//! # Layout
//!
//! A 32-byte header, then the payload: the exact part's length, the exact part (postcard, with
//! geometry that shapes share written once, `state/shared.rs`), then the snapshot (postcard,
//! each distinct shape written once):
//!
//! | bytes | what |
//! |---|---|
//! | 0–7 | `REBONDST` (a world), `REBONDSC` (a scene: [`crate::scene::Scene::save_state`]) |
//! | 8–11 | format version, little-endian `u32` ([`STATE_FORMAT_VERSION`]) |
//! | 12–19 | fingerprint of the engine's sources, little-endian `u64` |
//! | 20–27 | length of the payload, little-endian `u64` |
//! | 28–31 | CRC-32 (IEEE) of the payload, little-endian `u32` |
//! | 32–39 | length of the exact part, little-endian `u64` |
//! | 40– | the exact part, then the snapshot, whose first byte is its version (0 for the first) |
//!
//! Bytes that are not a state, of another format version, cut short or damaged are refused with
//! a [`StateError`] saying which, before anything is decoded: the checksum guards the decoders
//! against damage. Bytes made to match their checksum decode, so a decoded or rebuilt world's
//! invariants (indices in range, values finite and in range) are checked before it is handed
//! out; a snapshot's values go through the checks the public constructors make.

use std::fmt;

use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::World;

mod portable;
pub(crate) mod shared;

pub(crate) use portable::{NamedV1, SceneV1, SnapshotV5};
use portable::{Snapshot, SNAPSHOT_VERSIONS};

/// The format version this build writes and reads; states of other versions are refused. Version
/// 2 added the portable snapshot; every later version reads version 2's snapshots.
pub const STATE_FORMAT_VERSION: u32 = 2;

/// The first eight bytes of a world's state.
pub(crate) const WORLD_MAGIC: &[u8; 8] = b"REBONDST";

/// Length of the header, bytes.
const HEADER_LENGTH: usize = 32;

/// The fingerprint of this build's engine sources (`build.rs`).
fn source_fingerprint() -> u64 {
    u64::from_str_radix(env!("REBOND_SOURCE_FINGERPRINT"), 16).unwrap_or_default()
}

/// Why bytes could not be restored as a state.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum StateError {
    /// The bytes do not start as a state does.
    NotAState,
    /// A state of another format version.
    OtherVersion {
        /// The version the bytes say they are.
        found: u32,
    },
    /// A state written by a build of other engine sources whose portable snapshot is of a version
    /// newer than this build reads.
    OtherBuild,
    /// The bytes end before the state does.
    Truncated {
        /// Bytes the header announces, header included.
        expected: u64,
        /// Bytes there are.
        found: u64,
    },
    /// More bytes than the state: something was appended or the length was damaged.
    TrailingBytes {
        /// Bytes the header announces, header included.
        expected: u64,
        /// Bytes there are.
        found: u64,
    },
    /// The encoded world does not match its checksum.
    Damaged,
    /// The checksum matches but the world does not decode: what the decoder said.
    Undecodable(String),
    /// The world decodes but breaks an invariant of the engine's (an index out of range, a value
    /// that is not finite): bytes made to match their checksum. Which invariant.
    Inconsistent(String),
}

impl fmt::Display for StateError {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotAState => write!(formatter, "not a rebond state file"),
            Self::OtherVersion { found } => write!(
                formatter,
                "a state of format version {found}; this rebond reads version \
                 {STATE_FORMAT_VERSION}"
            ),
            Self::OtherBuild => write!(
                formatter,
                "a state written by a later build of rebond: its snapshot is of a version this \
                 rebond does not read"
            ),
            Self::Truncated { expected, found } => {
                write!(formatter, "truncated state: {found} bytes of {expected}")
            }
            Self::TrailingBytes { expected, found } => write!(
                formatter,
                "damaged state: {found} bytes where the header announces {expected}"
            ),
            Self::Damaged => write!(formatter, "damaged state: the checksum does not match"),
            Self::Undecodable(reason) => write!(formatter, "undecodable state: {reason}"),
            Self::Inconsistent(reason) => write!(formatter, "inconsistent state: {reason}"),
        }
    }
}

impl std::error::Error for StateError {}

/// `exact` encoded, then `snapshot`, behind the header starting with `magic`.
pub(crate) fn encode<T: Serialize>(magic: &[u8; 8], exact: &T, snapshot: SnapshotV5) -> Vec<u8> {
    // Every part of a world encodes: postcard fails only on types serde cannot describe
    // (maps with non-string keys and the like), which neither holds.
    let exact = shared::writing(|| postcard::to_stdvec(exact)).unwrap_or_default();
    let snapshot = postcard::to_stdvec(&Snapshot::V5(snapshot)).unwrap_or_default();
    let mut payload = Vec::with_capacity(8 + exact.len() + snapshot.len());
    payload.extend_from_slice(&(exact.len() as u64).to_le_bytes());
    payload.extend_from_slice(&exact);
    payload.extend_from_slice(&snapshot);
    let mut bytes = Vec::with_capacity(HEADER_LENGTH + payload.len());
    bytes.extend_from_slice(magic);
    bytes.extend_from_slice(&STATE_FORMAT_VERSION.to_le_bytes());
    bytes.extend_from_slice(&source_fingerprint().to_le_bytes());
    bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&crc32fast::hash(&payload).to_le_bytes());
    bytes.extend_from_slice(&payload);
    bytes
}

/// What a state gave: its exact part, when this build wrote it, or its portable snapshot.
pub(crate) enum Decoded<T> {
    Exact(T),
    Portable(Box<SnapshotV5>),
}

/// The exact part `bytes` encode behind a header starting with `magic` when the build that
/// wrote them is this one and `portable` is false, or else their portable snapshot, once the
/// header, length and checksum are checked.
pub(crate) fn decode<T: DeserializeOwned>(
    magic: &[u8; 8],
    bytes: &[u8],
    portable: bool,
) -> Result<Decoded<T>, StateError> {
    let starts_as_state = if bytes.len() < magic.len() {
        !bytes.is_empty() && magic.starts_with(bytes)
    } else {
        bytes.starts_with(magic)
    };
    if !starts_as_state {
        return Err(StateError::NotAState);
    }
    let Some(header) = bytes.get(..HEADER_LENGTH) else {
        return Err(StateError::Truncated {
            expected: HEADER_LENGTH as u64,
            found: bytes.len() as u64,
        });
    };
    let word = |bytes: &[u8], range: std::ops::Range<usize>| {
        bytes[range]
            .iter()
            .rev()
            .fold(0_u64, |sum, &byte| (sum << 8) | u64::from(byte))
    };
    let version = word(header, 8..12) as u32;
    if version != STATE_FORMAT_VERSION {
        return Err(StateError::OtherVersion { found: version });
    }
    let expected = (HEADER_LENGTH as u64).saturating_add(word(header, 20..28));
    let found = bytes.len() as u64;
    if found < expected {
        return Err(StateError::Truncated { expected, found });
    }
    if found > expected {
        return Err(StateError::TrailingBytes { expected, found });
    }
    let payload = &bytes[HEADER_LENGTH..];
    if crc32fast::hash(payload) != word(header, 28..32) as u32 {
        return Err(StateError::Damaged);
    }
    let exact_length = payload.get(..8).map(|length| word(length, 0..8));
    let Some((exact, snapshot)) = exact_length
        .and_then(|length| usize::try_from(length).ok()?.checked_add(8))
        .and_then(|end| Some((payload.get(8..end)?, payload.get(end..)?)))
    else {
        return Err(StateError::Undecodable(
            "the exact part runs past the state".to_owned(),
        ));
    };
    if !portable && word(header, 12..20) == source_fingerprint() {
        return crate::arena::reading_state(|| shared::reading(|| postcard::from_bytes(exact)))
            .map(Decoded::Exact)
            .map_err(|error| StateError::Undecodable(error.to_string()));
    }
    // A snapshot starts with its version's number: one past those this build knows is a later
    // build's, not damage.
    match postcard::take_from_bytes::<u32>(snapshot) {
        Ok((version, _)) if version >= SNAPSHOT_VERSIONS => return Err(StateError::OtherBuild),
        _ => {}
    }
    postcard::from_bytes::<Snapshot>(snapshot)
        .map(|snapshot| Decoded::Portable(Box::new(snapshot.into_latest())))
        .map_err(|error| StateError::Undecodable(format!("snapshot: {error}")))
}

impl World {
    /// The whole world as bytes (format in [`crate::state`]): restored by
    /// [`World::load_state`] in this build, it steps exactly as this world would; in any other
    /// build, later ones included, it is rebuilt from its portable snapshot, contacts cold.
    pub fn save_state(&self) -> Vec<u8> {
        encode(WORLD_MAGIC, self, SnapshotV5::of(self, None, Vec::new()))
    }

    /// A world saved by [`World::save_state`]; bytes that are not a state of this format
    /// version, or are cut short or damaged, are an error saying which.
    ///
    /// A state this build wrote is restored exactly; one another build wrote is rebuilt from its
    /// portable snapshot (the compatibility rule in [`crate::state`]: bodies, joints, handles,
    /// settings and sleep are kept; contacts start cold).
    ///
    /// The world restored is the saved one at the time of saving, with its identity: the saved
    /// world's handles name its bodies and joints (rolling a world back keeps its handles), and
    /// those of other worlds are refused. The state holds the identity, a number the process
    /// gave the world when it was made, so the states of two worlds built alike in one process
    /// differ in those bytes; a program that makes its worlds in the same order makes the same
    /// bytes each run.
    pub fn load_state(bytes: &[u8]) -> Result<World, StateError> {
        Self::load_state_from(bytes, false)
    }

    /// [`World::load_state`] as a build of other engine sources reads the bytes: from their
    /// portable snapshot, contacts cold. For tests of the snapshot.
    #[doc(hidden)]
    pub fn load_state_as_other_build(bytes: &[u8]) -> Result<World, StateError> {
        Self::load_state_from(bytes, true)
    }

    fn load_state_from(bytes: &[u8], portable: bool) -> Result<World, StateError> {
        match decode::<World>(WORLD_MAGIC, bytes, portable)? {
            Decoded::Exact(world) => {
                world.check_decoded().map_err(StateError::Inconsistent)?;
                Ok(world)
            }
            Decoded::Portable(snapshot) => {
                snapshot.restore_world().map_err(StateError::Inconsistent)
            }
        }
    }
}
