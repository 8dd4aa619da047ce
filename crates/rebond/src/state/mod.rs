//! Saving a world and restoring it exactly: [`World::save_state`] and [`World::load_state`].
//!
//! A state holds everything the next steps read (bodies, shapes, joints, the broad phase's tree,
//! the contact cache with its warm-start impulses, islands and sleep timers, settings, and the
//! solver's buffers), so a restored world steps bit for bit as the saved one would have.
//!
//! The bytes are a 32-byte header, then the world in postcard's compact binary encoding, with
//! geometry that shapes share (meshes, heightfields, hulls, compounds) written once
//! (`state/shared.rs`):
//!
//! | bytes | what |
//! |---|---|
//! | 0–7 | `REBONDST` (a world), `REBONDSC` (a scene: [`crate::scene::Scene::save_state`]) |
//! | 8–11 | format version, little-endian `u32` ([`STATE_FORMAT_VERSION`]) |
//! | 12–19 | fingerprint of the engine's sources, little-endian `u64` |
//! | 20–27 | length of the encoded world, little-endian `u64` |
//! | 28–31 | CRC-32 (IEEE) of the encoded world, little-endian `u32` |
//!
//! A state is the world's internal structures as they are, so only a build of the same engine
//! sources reads it back (the fingerprint says which); exact continuation needs the same binary
//! anyway. Bytes that are not a state, of another format version or build, cut short or damaged
//! are refused with a [`StateError`] saying which, before anything is decoded: the checksum
//! guards the decoder against damage. Bytes made to match their checksum decode, so a decoded
//! world's invariants (indices in range, values finite) are checked before it is handed out.

use std::fmt;

use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::World;

pub(crate) mod shared;

/// The format version this build writes and reads; states of other versions are refused.
pub const STATE_FORMAT_VERSION: u32 = 1;

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
    /// A state written by a build of other engine sources, whose structures may differ.
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
                "a state written by another build of rebond; only the build that wrote a state \
                 reads it"
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

/// `value` encoded, behind the header starting with `magic`.
pub(crate) fn encode<T: Serialize>(magic: &[u8; 8], value: &T) -> Vec<u8> {
    // Every part of a world encodes: postcard fails only on types serde cannot describe
    // (maps with non-string keys and the like), which the world does not hold.
    let payload = shared::writing(|| postcard::to_stdvec(value)).unwrap_or_default();
    let mut bytes = Vec::with_capacity(HEADER_LENGTH + payload.len());
    bytes.extend_from_slice(magic);
    bytes.extend_from_slice(&STATE_FORMAT_VERSION.to_le_bytes());
    bytes.extend_from_slice(&source_fingerprint().to_le_bytes());
    bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&crc32fast::hash(&payload).to_le_bytes());
    bytes.extend_from_slice(&payload);
    bytes
}

/// The value `bytes` encode behind a header starting with `magic`, once the header, length and
/// checksum are checked.
pub(crate) fn decode<T: DeserializeOwned>(magic: &[u8; 8], bytes: &[u8]) -> Result<T, StateError> {
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
    let word = |range: std::ops::Range<usize>| {
        header[range]
            .iter()
            .rev()
            .fold(0_u64, |sum, &byte| (sum << 8) | u64::from(byte))
    };
    let version = word(8..12) as u32;
    if version != STATE_FORMAT_VERSION {
        return Err(StateError::OtherVersion { found: version });
    }
    if word(12..20) != source_fingerprint() {
        return Err(StateError::OtherBuild);
    }
    let expected = (HEADER_LENGTH as u64).saturating_add(word(20..28));
    let found = bytes.len() as u64;
    if found < expected {
        return Err(StateError::Truncated { expected, found });
    }
    if found > expected {
        return Err(StateError::TrailingBytes { expected, found });
    }
    let payload = &bytes[HEADER_LENGTH..];
    if crc32fast::hash(payload) != word(28..32) as u32 {
        return Err(StateError::Damaged);
    }
    crate::arena::reading_state(|| shared::reading(|| postcard::from_bytes(payload)))
        .map_err(|error| StateError::Undecodable(error.to_string()))
}

impl World {
    /// The whole world as bytes (format in [`crate::state`]): restored by
    /// [`World::load_state`], it steps exactly as this world would.
    pub fn save_state(&self) -> Vec<u8> {
        encode(WORLD_MAGIC, self)
    }

    /// A world saved by [`World::save_state`]; bytes that are not a state of this format
    /// version, or are cut short or damaged, are an error saying which.
    ///
    /// The world restored is the saved one at the time of saving, with its identity: the saved
    /// world's handles name its bodies and joints (rolling a world back keeps its handles), and
    /// those of other worlds are refused. The state holds the identity, a number the process
    /// gave the world when it was made, so the states of two worlds built alike in one process
    /// differ in those bytes; a program that makes its worlds in the same order makes the same
    /// bytes each run.
    pub fn load_state(bytes: &[u8]) -> Result<World, StateError> {
        let world: World = decode(WORLD_MAGIC, bytes)?;
        world.check_decoded().map_err(StateError::Inconsistent)?;
        Ok(world)
    }
}
