//! What keeps the module well-behaved under the things Python programs do: Ctrl-C during a long
//! `step(n)`, absurd batch sizes, a second thread touching an object while it steps, and whole
//! numbers too large for the engine.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::time::{Duration, Instant};

use pyo3::exceptions::{PyMemoryError, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyInt, PyString};
use pyo3::PyClass;

use crate::batch::Batch;
use crate::sim::Sim;
use crate::world::World;

/// How long a `step(n)` runs without the GIL before it takes the GIL back for a moment to let
/// Python see Ctrl-C: a tenth of a second is quick enough for a person at the keyboard and long
/// enough that the round trips (tens of microseconds) cost nothing measurable.
const SIGNAL_CHECK_EVERY: Duration = Duration::from_millis(100);

/// The `n` of `step(n)`: a whole number from 0 to 2⁶⁴ - 1, errors naming `n` with the value as
/// given.
#[derive(Debug, Clone, Copy)]
pub struct StepCount(pub u64);

impl<'py> FromPyObject<'py> for StepCount {
    fn extract_bound(value: &Bound<'py, PyAny>) -> PyResult<Self> {
        whole_number(value, "n", 0).map(Self)
    }
}

/// `value` as a whole number from `least` to 2⁶⁴ - 1; `name` is the argument's, for errors,
/// which quote the value as Python writes it (`n: must be at most 18446744073709551615, got
/// 1180591620717411303424`).
pub fn whole_number(value: &Bound<'_, PyAny>, name: &str, least: u64) -> PyResult<u64> {
    let below = |text: &dyn std::fmt::Display| {
        let rule = match least {
            0 => "must not be negative".to_owned(),
            _ => format!("must be at least {least}"),
        };
        PyValueError::new_err(format!("{name}: {rule}, got {text}"))
    };
    if let Ok(number) = value.extract::<u64>() {
        return if number >= least {
            Ok(number)
        } else {
            Err(below(&number))
        };
    }
    let is_whole = value.downcast::<PyBool>().is_err()
        && (value.downcast::<PyInt>().is_ok() || value.hasattr("__index__")?);
    if !is_whole {
        let type_name = value.get_type().name()?;
        return Err(PyTypeError::new_err(format!(
            "{name}: expected a whole number, got a {type_name}"
        )));
    }
    let text = value.str()?;
    if text.to_cow()?.starts_with('-') {
        return Err(below(&text));
    }
    Err(PyValueError::new_err(format!(
        "{name}: must be at most {}, got {text}",
        u64::MAX
    )))
}

/// Runs `n` steps as rounds of `round(k)` steps, each without the GIL, checking for Ctrl-C (and
/// any other Python signal) between rounds. Rounds grow from one step until one takes about
/// [`SIGNAL_CHECK_EVERY`]. The steps are the same however they are split, so the result is bit
/// for bit that of one uninterrupted run; an interrupted run stops at the end of a round, after
/// a whole number of steps, with the world as those steps left it.
pub fn step_in_rounds<E>(
    py: Python<'_>,
    n: u64,
    mut round: impl FnMut(u64) -> Result<(), E> + Send,
) -> PyResult<Result<(), E>>
where
    E: Send,
{
    let mut done = 0;
    let mut size = 1u64;
    while done < n {
        let steps = size.min(n - done);
        let started = Instant::now();
        let result = py.allow_threads(|| round(steps));
        if result.is_err() {
            return Ok(result);
        }
        done += steps;
        py.check_signals()?;
        // The clock only decides where the rounds end, never what a step computes.
        let elapsed = started.elapsed();
        if elapsed < SIGNAL_CHECK_EVERY / 2 {
            size = size.saturating_mul(2);
        } else if elapsed > SIGNAL_CHECK_EVERY * 2 {
            size = (size / 2).max(1);
        }
    }
    Ok(Ok(()))
}

/// Bytes allocated so far by the calling thread (never decreased by frees), to measure what a
/// copy of a world takes.
fn allocated_here() -> usize {
    ALLOCATED.with(Cell::get)
}

thread_local! {
    static ALLOCATED: Cell<usize> = const { Cell::new(0) };
}

/// The system allocator, counting each thread's allocations in [`ALLOCATED`]: a thread-local add,
/// no atomics, and nothing at all in a steady-state step, which does not allocate.
struct CountingAllocator;

// SAFETY: every call is forwarded unchanged to `System`; the counter only observes the sizes.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count(layout.size());
        // SAFETY: the caller's contract for `alloc` is `System.alloc`'s.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count(layout.size());
        // SAFETY: as `alloc`.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count(new_size.saturating_sub(layout.size()));
        // SAFETY: the caller's contract for `realloc` is `System.realloc`'s.
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract for `dealloc` is `System.dealloc`'s.
        unsafe { System.dealloc(ptr, layout) }
    }
}

/// Adds `bytes` to the calling thread's count; a thread being torn down is not counted.
fn count(bytes: usize) {
    let _ = ALLOCATED.try_with(|allocated| allocated.set(allocated.get().wrapping_add(bytes)));
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// `count` copies of `initial` for a batch, or `MemoryError` when they cannot fit. One copy is
/// made first and what it allocated measured; `count` times that must fit in the memory the
/// system has available, so that an impossible count fails at once instead of the allocator
/// aborting the interpreter (or the system killing it) partway through the copies.
pub fn copies(initial: &Sim, count: usize) -> PyResult<Vec<Sim>> {
    let before = allocated_here();
    let first = initial.clone();
    let per_world = std::mem::size_of::<Sim>() + allocated_here().wrapping_sub(before);
    let Some(needed) = per_world.checked_mul(count) else {
        return Err(PyMemoryError::new_err(format!(
            "count: {count} worlds of {per_world} bytes need more memory than a machine can \
             address"
        )));
    };
    if let Some(available) = available_memory() {
        if needed > available {
            return Err(PyMemoryError::new_err(format!(
                "count: {count} worlds of {per_world} bytes need {needed} bytes, more than the \
                 {available} bytes of memory available"
            )));
        }
    }
    let mut sims = Vec::new();
    sims.try_reserve_exact(count).map_err(|_| {
        PyMemoryError::new_err(format!("count: no memory for the list of {count} worlds"))
    })?;
    sims.resize(count, first);
    Ok(sims)
}

/// The memory the system can still give, bytes: its available memory and free swap, from
/// Linux's `/proc/meminfo`; `None` where that cannot be read (the fallible reservation of the
/// list is then the only guard).
fn available_memory() -> Option<usize> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let field = |name: &str| -> Option<usize> {
        let line = meminfo.lines().find(|line| line.starts_with(name))?;
        let kilobytes: usize = line.split_whitespace().nth(1)?.parse().ok()?;
        kilobytes.checked_mul(1024)
    };
    Some(field("MemAvailable:")?.saturating_add(field("SwapFree:").unwrap_or(0)))
}

/// The attribute `name` of `object` as Python's default lookup finds it, or a clear error while
/// another thread holds the object (stepping it, most often), where PyO3 would say only "Already
/// mutably borrowed" when the method is called.
fn guarded_getattr<'py, T>(
    object: &Bound<'py, T>,
    name: &Bound<'py, PyString>,
) -> PyResult<Bound<'py, PyAny>>
where
    T: PyClass<Frozen = pyo3::pyclass::boolean_struct::False>,
{
    if object.try_borrow_mut().is_err() {
        let kind = T::NAME;
        return Err(PyRuntimeError::new_err(format!(
            "{kind}.{name}: this {kind} is in use by another thread (a call such as step(n) is \
             running on it); use each {kind} from one thread at a time, or guard it with a lock"
        )));
    }
    // SAFETY: both pointers are valid, owned by the `Bound`s for the call, and the GIL is held;
    // the result is a new reference or null with the error set, as `from_owned_ptr_or_err` takes.
    unsafe {
        let raw = pyo3::ffi::PyObject_GenericGetAttr(object.as_ptr(), name.as_ptr());
        Bound::from_owned_ptr_or_err(object.py(), raw)
    }
}

/// Each class's attribute lookup: [`guarded_getattr`].
macro_rules! guarded_lookup {
    ($($class:ty),*) => {$(
        #[pymethods]
        impl $class {
            /// Attribute lookup that refuses, with a clear message, while another thread holds
            /// the object.
            fn __getattribute__<'py>(
                slf: &Bound<'py, Self>,
                name: &Bound<'py, PyString>,
            ) -> PyResult<Bound<'py, PyAny>> {
                guarded_getattr(slf, name)
            }
        }
    )*};
}

guarded_lookup!(World, Batch);
