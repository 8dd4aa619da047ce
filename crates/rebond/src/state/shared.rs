//! Geometry shared between shapes (`Arc`s: meshes, heightfields, hulls, compounds) written once
//! per state and shared again when it is read, instead of once per body and restored as copies.
//!
//! Within [`writing`], the first time an `Arc` is met its value is written and it is given the
//! next number; later meetings write only that number. Numbers are given once a value is
//! written, after what it holds, so that [`reading`] gives them in the same order, as each value
//! is read. Outside those scopes (any other use of serde) every `Arc` is written whole.

use std::any::Any;
use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::Arc;

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

type Shared = Arc<dyn Any + Send + Sync>;

thread_local! {
    /// While writing: each `Arc` written so far, by address, with its number.
    static WRITTEN: RefCell<Option<HashMap<usize, u32>>> = const { RefCell::new(None) };
    /// While reading: each `Arc` read so far, by number.
    static READ: RefCell<Option<Vec<Shared>>> = const { RefCell::new(None) };
}

/// A shared value as written: whole the first time, then by its number.
#[derive(Serialize)]
enum Written<'a, T> {
    Whole(&'a T),
    Again(u32),
}

/// A shared value as read.
#[derive(Deserialize)]
enum Read<T> {
    Whole(T),
    Again(u32),
}

/// Runs `write` with shared values written once.
pub(super) fn writing<R>(write: impl FnOnce() -> R) -> R {
    WRITTEN.set(Some(HashMap::new()));
    let result = write();
    WRITTEN.set(None);
    result
}

/// Runs `read` with shared values read once and shared.
pub(super) fn reading<R>(read: impl FnOnce() -> R) -> R {
    READ.set(Some(Vec::new()));
    let result = read();
    READ.set(None);
    result
}

/// `serde(with)` serialisation of an `Arc` written once per state.
pub(crate) fn serialize<T: Serialize, S: Serializer>(
    value: &Arc<T>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    let address = Arc::as_ptr(value) as usize;
    let number = WRITTEN.with_borrow(|written| written.as_ref()?.get(&address).copied());
    if let Some(number) = number {
        return Written::<T>::Again(number).serialize(serializer);
    }
    let done = Written::Whole(&**value).serialize(serializer)?;
    WRITTEN.with_borrow_mut(|written| {
        if let Some(written) = written {
            let number = written.len() as u32;
            written.insert(address, number);
        }
    });
    Ok(done)
}

/// `serde(with)` deserialisation of an `Arc` written by [`serialize`].
pub(crate) fn deserialize<'de, T, D>(deserializer: D) -> Result<Arc<T>, D::Error>
where
    T: Deserialize<'de> + Send + Sync + 'static,
    D: Deserializer<'de>,
{
    match Read::<T>::deserialize(deserializer)? {
        Read::Whole(value) => {
            let value = Arc::new(value);
            READ.with_borrow_mut(|read| {
                if let Some(read) = read {
                    read.push(value.clone());
                }
            });
            Ok(value)
        }
        Read::Again(number) => READ
            .with_borrow(|read| read.as_ref()?.get(number as usize).cloned())
            .and_then(|shared| shared.downcast::<T>().ok())
            .ok_or_else(|| D::Error::custom(format!("shared geometry {number} was never read"))),
    }
}
