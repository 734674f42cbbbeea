//! A small deterministic random generator (xorshift64*): the same seed gives the same cases on every
//! machine, so a failing run can be repeated with `--seed`.

pub struct Random(u64);

impl Random {
    pub fn new(seed: u64) -> Random {
        // A zero state would stay zero forever; mixing the seed also spreads nearby seeds apart.
        Random(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    pub fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A number in `0..bound` (0 when `bound` is 0).
    pub fn below(&mut self, bound: usize) -> usize {
        if bound == 0 {
            return 0;
        }
        (self.next() % bound as u64) as usize
    }

    /// True with probability 1 in `n`.
    pub fn one_in(&mut self, n: usize) -> bool {
        self.below(n) == 0
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }

    /// A length that is usually small and sometimes large: the sizes where bugs hide are both.
    pub fn length(&mut self, usual: usize, rare: usize) -> usize {
        if self.one_in(16) {
            self.below(rare + 1)
        } else {
            self.below(usual + 1)
        }
    }
}

impl Random {
    /// One of `words`.
    pub fn word(&mut self, words: &[&'static str]) -> &'static str {
        words[self.below(words.len())]
    }
}
