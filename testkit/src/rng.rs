//! The one seeded random generator of the tests, benchmarks and examples.
//!
//! Three streams are in use, and each caller's numbers must stay what they
//! are (stress pairs, motion tables and test cases are named by their
//! seeds), so [`Rng`] is one type with one constructor per stream:
//!
//! - [`Rng::stream`]: SplitMix64 (Steele, Lea & Flood, "Fast splittable
//!   pseudorandom number generators") keyed by `(seed, index)`, so that
//!   every stress pair has a stream of its own;
//! - [`Rng::xorshift`]: Marsaglia's xorshift64 (shifts 13, 7, 17; "Xorshift
//!   RNGs"), whose output is its state;
//! - [`Rng::xorshift_star`]: Vigna's xorshift64* (shifts 12, 25, 27 and a
//!   multiply; "An experimental exploration of Marsaglia's xorshift
//!   generators, scrambled").
//!
//! Every draw ([`Rng::unit`], [`Rng::range`], [`Rng::int`], ...) is built
//! on [`Rng::next_u64`], the same way for all three.

/// The step of a stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Step {
    SplitMix,
    XorShift,
    XorShiftStar,
}

/// A seeded random generator: fully determined by its constructor's
/// arguments (see the module docs for the three streams).
#[derive(Clone, Debug)]
pub struct Rng {
    state: u64,
    step: Step,
}

/// One xorshift64 step (shifts 13, 7, 17) of `state`; returns the new
/// state, which is also the output. A zero state stays zero.
pub fn xorshift64(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// The top 53 bits of `bits` as a float uniform in [0, 1).
pub fn unit_from_bits(bits: u64) -> f64 {
    (bits >> 11) as f64 / (1u64 << 53) as f64
}

impl Rng {
    /// The SplitMix64 stream of `(seed, index)`: pair `index` of a run
    /// seeded with `seed` draws from this stream alone.
    pub fn stream(seed: u64, index: u64) -> Rng {
        let mut r = Rng {
            state: seed ^ index.wrapping_mul(0xA076_1D64_78BD_642F),
            step: Step::SplitMix,
        };
        r.next_u64();
        r.next_u64();
        r
    }

    /// The xorshift64 stream from `state` (not zero: a zero state gives
    /// zeros forever).
    pub fn xorshift(state: u64) -> Rng {
        Rng {
            state,
            step: Step::XorShift,
        }
    }

    /// The xorshift64* stream from `state` (not zero, as for
    /// [`Rng::xorshift`]).
    pub fn xorshift_star(state: u64) -> Rng {
        Rng {
            state,
            step: Step::XorShiftStar,
        }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        match self.step {
            Step::SplitMix => {
                self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
                let mut z = self.state;
                z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                z ^ (z >> 31)
            }
            Step::XorShift => xorshift64(&mut self.state),
            Step::XorShiftStar => {
                self.state ^= self.state >> 12;
                self.state ^= self.state << 25;
                self.state ^= self.state >> 27;
                self.state.wrapping_mul(0x2545_F491_4F6C_DD1D)
            }
        }
    }

    /// Uniform in [0, 1) (53 random bits).
    pub fn unit(&mut self) -> f64 {
        unit_from_bits(self.next_u64())
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// 10^u with u uniform in [lo, hi): log-uniform between 10^lo and 10^hi.
    pub fn pow10(&mut self, lo: f64, hi: f64) -> f64 {
        10f64.powf(self.range(lo, hi))
    }

    /// An integer in [0, k) (the remainder of 64 bits, so very slightly
    /// biased for large k). Panics when k is 0.
    pub fn below(&mut self, k: u64) -> u64 {
        self.next_u64() % k
    }

    /// An index in [0, k), as [`Rng::below`].
    pub fn index(&mut self, k: usize) -> usize {
        self.below(k as u64) as usize
    }

    /// An integer in [lo, hi] (inclusive), as [`Rng::below`].
    pub fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + self.index(hi - lo + 1)
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// One element of `items` (not empty).
    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.int(0, items.len() - 1)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The three streams against the reference algorithms written out
    /// independently here, and known first values.
    #[test]
    fn streams_follow_their_reference_algorithms() {
        // SplitMix64 from 0: the published first output of the reference
        // implementation (Vigna's splitmix64.c) is 0xe220a8397b1dcdaf.
        let mut r = Rng {
            state: 0,
            step: Step::SplitMix,
        };
        assert_eq!(r.next_u64(), 0xe220_a839_7b1d_cdaf);

        let mut x = Rng::xorshift(1);
        // 1 -> 1 ^ 1<<13 = 0x2001; ^ >>7 = 0x2001 ^ 0x40 = 0x2041;
        // ^ <<17 = 0x2041 ^ 0x4082_0000 = 0x4082_2041.
        assert_eq!(x.next_u64(), 0x4082_2041);

        let (mut s, mut star) = (7u64, Rng::xorshift_star(7));
        for _ in 0..100 {
            s ^= s >> 12;
            s ^= s << 25;
            s ^= s >> 27;
            assert_eq!(star.next_u64(), s.wrapping_mul(0x2545_F491_4F6C_DD1D));
        }
    }

    #[test]
    fn draws_stay_in_their_ranges() {
        for seed in 1..50u64 {
            for mut r in [
                Rng::stream(seed, seed * 3),
                Rng::xorshift(seed),
                Rng::xorshift_star(seed),
            ] {
                for _ in 0..200 {
                    let u = r.unit();
                    assert!((0.0..1.0).contains(&u));
                    let v = r.range(-2.0, 3.0);
                    assert!((-2.0..3.0).contains(&v));
                    let i = r.int(4, 9);
                    assert!((4..=9).contains(&i));
                    assert!(r.below(5) < 5);
                    let p = r.pow10(-3.0, 2.0);
                    assert!((1e-3..1e2).contains(&p));
                }
            }
        }
    }

    /// Different pair indices of one seed give different streams.
    #[test]
    fn stream_indices_differ() {
        let firsts: std::collections::BTreeSet<u64> =
            (0..1000).map(|i| Rng::stream(5, i).next_u64()).collect();
        assert_eq!(firsts.len(), 1000);
    }
}
