//! Where a jump lands: `GOTOF` searches towards the end of the program, `GOTOB` towards its start,
//! `GOTO` and `GOTOC` forward first and then backward (reference §8.4). Shared by navigation, the
//! cross-file diagnostics and renumbering, so that all three agree on which block a jump reaches.

use crate::syntax::ast::JumpKind;

/// The outcome of searching a jump's target among the lines that carry it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JumpResolution {
    /// The line the jump reaches.
    Found(usize),
    /// The target exists only in the other direction (a `GOTOF` to a label above): the nearest such line.
    WrongDirection(usize),
    /// No line carries the target.
    Missing,
}

/// Resolves a jump of `kind` written on `from` among `candidates` (lines in ascending order). A target
/// on the jump's own line is accepted in either direction: whether the control finds it is not
/// documented, and unknown is not wrong.
pub fn resolve_jump(kind: JumpKind, from: usize, candidates: &[usize]) -> JumpResolution {
    let first_after = candidates.iter().copied().find(|line| *line > from);
    let last_before = candidates.iter().copied().rev().find(|line| *line < from);
    let same_line = candidates.contains(&from);
    let found = match kind {
        JumpKind::Gotof => first_after.or(same_line.then_some(from)),
        JumpKind::Gotob => last_before.or(same_line.then_some(from)),
        JumpKind::Goto | JumpKind::Gotoc => {
            first_after.or(same_line.then_some(from)).or(last_before)
        }
        JumpKind::Gotos => return JumpResolution::Missing,
    };
    match (found, kind) {
        (Some(line), _) => JumpResolution::Found(line),
        (None, JumpKind::Gotof) => {
            last_before.map_or(JumpResolution::Missing, JumpResolution::WrongDirection)
        }
        (None, JumpKind::Gotob) => {
            first_after.map_or(JumpResolution::Missing, JumpResolution::WrongDirection)
        }
        (None, _) => JumpResolution::Missing,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_are_followed() {
        let lines = [2, 8];
        assert_eq!(
            resolve_jump(JumpKind::Gotof, 5, &lines),
            JumpResolution::Found(8)
        );
        assert_eq!(
            resolve_jump(JumpKind::Gotob, 5, &lines),
            JumpResolution::Found(2)
        );
        assert_eq!(
            resolve_jump(JumpKind::Gotof, 9, &lines),
            JumpResolution::WrongDirection(8)
        );
        assert_eq!(
            resolve_jump(JumpKind::Gotob, 1, &lines),
            JumpResolution::WrongDirection(2)
        );
        assert_eq!(
            resolve_jump(JumpKind::Goto, 9, &lines),
            JumpResolution::Found(8)
        );
        assert_eq!(
            resolve_jump(JumpKind::Goto, 0, &lines),
            JumpResolution::Found(2)
        );
        assert_eq!(
            resolve_jump(JumpKind::Gotoc, 0, &[]),
            JumpResolution::Missing
        );
        assert_eq!(
            resolve_jump(JumpKind::Gotof, 8, &lines),
            JumpResolution::Found(8)
        );
    }
}
