//! Graph colouring of the contact constraints into lane sets: up to four constraints that share
//! no moving body, which the solver solves at once (one per SIMD lane) with the result solving
//! them one after another gives.
//!
//! Greedy, in constraint order (which is contact order, so deterministic), with a few colours
//! open at a time: each constraint joins the lowest open colour neither of its bodies is in yet.
//! When a colour holds four constraints it becomes a lane set, and its bodies are free for that
//! colour again. So lane sets follow the contact order closely, and a stack is solved nearly
//! from the bottom up as before; colouring the whole scene at once (Box2D v3) puts every other
//! contact of a column in one colour, and measured, the 20-row pyramid of the tests then drifted
//! 7.5 cm instead of under 5 cm. Solver body 0, which stands for every static or sleeping body,
//! never changes velocity and does not count. A constraint whose bodies are in every open colour
//! goes to the overflow: lane sets of one constraint each, solved after the others.

use super::wide::LANES;

/// Colours open at a time. A box in a stack or a pile touches about a dozen others, and the
/// colours fill quickly; more open colours do not make the bench's stacks or piles faster.
pub const OPEN_COLOURS: usize = 8;

/// The lane sets of one step's constraints, in buffers reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct GraphColouring {
    /// Per solver body, bit `c` set while the open colour `c` holds a constraint on it.
    body_colours: Vec<u32>,
    /// The constraints of each open colour, at most [`LANES`].
    open: [Vec<usize>; OPEN_COLOURS],
    /// The constraint indices of every lane set, one set after another.
    members: Vec<usize>,
    /// Where each lane set ends in `members`.
    set_ends: Vec<usize>,
    /// Constraints that found no open colour, ascending: each becomes a lane set of its own,
    /// after the others.
    overflow: Vec<usize>,
}

impl GraphColouring {
    /// Colours the constraints between the solver bodies `pairs` (indexed by constraint;
    /// `body_count` solver bodies, body 0 the fixed one).
    pub fn colour(&mut self, pairs: &[(usize, usize)], body_count: usize) {
        self.body_colours.clear();
        self.body_colours.resize(body_count, 0);
        self.members.clear();
        self.set_ends.clear();
        self.overflow.clear();
        for (index, &(body_a, body_b)) in pairs.iter().enumerate() {
            let used = self.moving_colours(body_a) | self.moving_colours(body_b);
            let colour = used.trailing_ones() as usize;
            if colour >= OPEN_COLOURS {
                self.overflow.push(index);
                continue;
            }
            self.mark(pairs[index], colour, true);
            self.open[colour].push(index);
            if self.open[colour].len() == LANES {
                for position in 0..LANES {
                    self.mark(pairs[self.open[colour][position]], colour, false);
                }
                self.close(colour);
            }
        }
        for colour in 0..OPEN_COLOURS {
            if !self.open[colour].is_empty() {
                self.close(colour);
            }
        }
        for &index in &self.overflow {
            self.members.push(index);
            self.set_ends.push(self.members.len());
        }
    }

    /// Sets or clears `colour` at both bodies (never at body 0).
    fn mark(&mut self, (body_a, body_b): (usize, usize), colour: usize, set: bool) {
        for body in [body_a, body_b] {
            if body != 0 {
                if set {
                    self.body_colours[body] |= 1 << colour;
                } else {
                    self.body_colours[body] &= !(1 << colour);
                }
            }
        }
    }

    /// Turns the open colour into the next lane set and empties it.
    fn close(&mut self, colour: usize) {
        self.members.extend_from_slice(&self.open[colour]);
        self.set_ends.push(self.members.len());
        self.open[colour].clear();
    }

    /// The colours already taken at `body`; none at the fixed body 0.
    fn moving_colours(&self, body: usize) -> u32 {
        if body == 0 {
            0
        } else {
            self.body_colours[body]
        }
    }

    /// The constraint indices of each lane set, in solving order.
    pub fn lane_sets(&self) -> impl Iterator<Item = &[usize]> {
        let starts = std::iter::once(0).chain(self.set_ends.iter().copied());
        starts
            .zip(&self.set_ends)
            .map(|(start, &end)| &self.members[start..end])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lane_sets(colouring: &GraphColouring) -> Vec<Vec<usize>> {
        colouring.lane_sets().map(<[usize]>::to_vec).collect()
    }

    #[test]
    fn a_lane_set_shares_no_moving_body_and_follows_the_contact_order() {
        // A column: ground (body 0) under body 1, then 1–2, 2–3, … 9–10.
        let pairs: Vec<_> = (0..10).map(|i| (i, i + 1)).collect();
        let mut colouring = GraphColouring::default();
        colouring.colour(&pairs, 11);
        assert_eq!(
            lane_sets(&colouring),
            [vec![0, 2, 4, 6], vec![1, 3, 5, 8], vec![7, 9]]
        );
    }

    #[test]
    fn a_body_in_every_open_colour_overflows_into_sets_of_one() {
        let pairs: Vec<_> = (0..OPEN_COLOURS + 2).map(|other| (1, other + 2)).collect();
        let mut colouring = GraphColouring::default();
        colouring.colour(&pairs, OPEN_COLOURS + 4);
        assert!(colouring.lane_sets().all(|members| members.len() == 1));
        let last: Vec<_> = colouring.lane_sets().skip(OPEN_COLOURS).collect();
        assert_eq!(last, [[OPEN_COLOURS], [OPEN_COLOURS + 1]]);
    }
}
