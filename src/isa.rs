//! The instruction set the hot loops use, chosen at run time: the build targets the plain
//! x86-64 baseline (so one binary runs on any x86-64 processor), and the BVH's box tests
//! switch to AVX2 where the processor has it. Both paths compute the same IEEE operations
//! lane by lane (no fused multiply-adds), so they make the same images bit for bit; the
//! environment variable `PRISM_ISA` forces either, for tests and for comparing speed.

use std::sync::atomic::{AtomicU8, Ordering};

/// A set of instructions for the lanes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InstructionSet {
    /// Eight lanes as two halves of four: SSE2 on x86-64, plain arrays (which the compiler
    /// may vectorise) elsewhere. Every processor runs it.
    Baseline,
    /// Eight lanes in one register with AVX2, on x86-64 processors that have it.
    Avx2,
}

/// The environment variable that forces a path.
pub const VARIABLE: &str = "PRISM_ISA";

/// Why a forced instruction set cannot be used.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum IsaError {
    /// A name that is none of `auto`, `baseline`, `avx2`.
    #[error("{VARIABLE}={0:?} is not an instruction set prism knows: use auto, baseline or avx2")]
    Unknown(String),
    /// A set the processor lacks.
    #[error("{VARIABLE}={0} asks for an instruction set this processor does not have")]
    Unsupported(&'static str),
}

impl InstructionSet {
    /// Every set, for reading a name.
    const ALL: [InstructionSet; 2] = [InstructionSet::Baseline, InstructionSet::Avx2];

    /// Its name, as `PRISM_ISA` takes it.
    pub fn name(self) -> &'static str {
        match self {
            InstructionSet::Baseline => "baseline",
            InstructionSet::Avx2 => "avx2",
        }
    }

    /// Whether this processor can run it.
    pub fn is_supported(self) -> bool {
        match self {
            InstructionSet::Baseline => true,
            InstructionSet::Avx2 => avx2_present(),
        }
    }

    /// The fastest set this processor runs.
    pub fn best() -> InstructionSet {
        if avx2_present() {
            InstructionSet::Avx2
        } else {
            InstructionSet::Baseline
        }
    }

    fn code(self) -> u8 {
        match self {
            InstructionSet::Baseline => 1,
            InstructionSet::Avx2 => 2,
        }
    }
}

fn avx2_present() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::arch::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    return false;
}

/// The set in use: 0 until chosen, then `InstructionSet::code`.
static ACTIVE: AtomicU8 = AtomicU8::new(0);

/// The instruction set in use: the one chosen, else the one `PRISM_ISA` names, else the
/// best this processor runs. (The `prism` command refuses a `PRISM_ISA` it cannot follow
/// before it starts; a library user that never chooses gets the best set instead.)
#[inline(always)]
pub fn active() -> InstructionSet {
    // Asked before every mesh traversal: the common case in line, the first choice apart.
    match ACTIVE.load(Ordering::Relaxed) {
        1 => InstructionSet::Baseline,
        2 => InstructionSet::Avx2,
        _ => choose_first(),
    }
}

/// The set `active` uses when none has been chosen yet.
#[cold]
#[inline(never)]
fn choose_first() -> InstructionSet {
    let set = from_environment()
        .ok()
        .flatten()
        .filter(|set| set.is_supported())
        .unwrap_or_else(InstructionSet::best);
    ACTIVE.store(set.code(), Ordering::Relaxed);
    set
}

/// The set `PRISM_ISA` names, if it is set.
fn from_environment() -> Result<Option<InstructionSet>, IsaError> {
    std::env::var_os(VARIABLE)
        .map(|value| parse(&value.to_string_lossy()))
        .transpose()
}

/// Uses `set` from now on, in every thread. Refused where the processor lacks it.
pub fn choose(set: InstructionSet) -> Result<(), IsaError> {
    if !set.is_supported() {
        return Err(IsaError::Unsupported(set.name()));
    }
    ACTIVE.store(set.code(), Ordering::Relaxed);
    Ok(())
}

/// Reads a value of `PRISM_ISA`: `auto` (the best the processor runs; also an empty
/// value, as shells leave a variable set to nothing), `baseline` or `avx2`. Case and
/// surrounding spaces do not matter.
pub fn parse(value: &str) -> Result<InstructionSet, IsaError> {
    let wanted = value.trim().to_ascii_lowercase();
    if wanted.is_empty() || wanted == "auto" {
        return Ok(InstructionSet::best());
    }
    InstructionSet::ALL
        .into_iter()
        .find(|set| set.name() == wanted)
        .ok_or_else(|| IsaError::Unknown(value.to_string()))
}

/// Chooses the set `PRISM_ISA` names, if it is set; returns the set in use.
pub fn choose_from_environment() -> Result<InstructionSet, IsaError> {
    if let Some(set) = from_environment()? {
        choose(set)?;
    }
    Ok(active())
}

/// The AVX engine for the box tests, where the set in use is AVX2.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn avx2_lanes() -> Option<crate::simd::Avx> {
    if active() == InstructionSet::Avx2 {
        crate::simd::Avx::new()
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_of_the_variable_are_read_or_refused_by_name() {
        assert_eq!(parse("baseline"), Ok(InstructionSet::Baseline));
        assert_eq!(parse(" AVX2 "), Ok(InstructionSet::Avx2));
        assert_eq!(parse("auto"), Ok(InstructionSet::best()));
        assert_eq!(parse(" "), Ok(InstructionSet::best()));
        let refused = parse("avx512").unwrap_err();
        assert_eq!(refused, IsaError::Unknown("avx512".into()));
        assert!(refused.to_string().contains("use auto, baseline or avx2"));
    }

    #[test]
    fn the_baseline_runs_everywhere_and_the_best_is_supported() {
        assert!(InstructionSet::Baseline.is_supported());
        assert!(InstructionSet::best().is_supported());
        if !InstructionSet::Avx2.is_supported() {
            assert_eq!(
                choose(InstructionSet::Avx2),
                Err(IsaError::Unsupported("avx2"))
            );
        }
    }
}
