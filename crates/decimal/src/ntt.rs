//! Big-integer multiplication by number-theoretic transforms, for the operand sizes where
//! num-bigint's Toom-3 gets slow (tens of thousands of bits and up).
//!
//! The 64-bit limbs of both operands are the coefficients of two polynomials; their product
//! is computed modulo three primes `p < 2^62` with `p - 1` divisible by `2^32` (cyclic
//! convolutions by radix-2 transforms), and put back together by the Chinese remainder
//! theorem. Each coefficient of the product is below `min(len) * 2^128 < p1 p2 p3 ~ 2^186`,
//! so the result is exact for operands of up to `2^57` limbs.
//!
//! Arithmetic is Montgomery's (`R = 2^64`) with lazy reduction: values live in `[0, 2p)`
//! between butterflies, which needs `4p < 2^64`. Twiddle factors are cached per process,
//! grown on demand (the table for a transform of length `n` is a prefix of any longer one).

use std::sync::{Arc, Mutex, PoisonError};

use num_bigint::BigUint;

/// One NTT prime with its Montgomery constants.
struct Prime {
    p: u64,
    /// `-p^-1 mod 2^64` is not used: the variant below needs `p^-1 mod 2^64`.
    p_inv: u64,
    /// `2^128 mod p`, to bring a value into Montgomery form.
    r2: u64,
    /// A generator of the multiplicative group.
    generator: u64,
}

impl Prime {
    const fn new(p: u64, generator: u64) -> Prime {
        // p^-1 mod 2^64 by Newton's iteration (each step doubles the correct low bits).
        let mut inv = p; // correct to 3 bits for odd p
        let mut i = 0;
        while i < 6 {
            inv = inv.wrapping_mul(2u64.wrapping_sub(p.wrapping_mul(inv)));
            i += 1;
        }
        let r = (1u128 << 64) % p as u128;
        let r2 = (r * r) % p as u128;
        Prime {
            p,
            p_inv: inv,
            r2: r2 as u64,
            generator,
        }
    }

    /// `a * b / 2^64 mod p`, in `(0, 2p)`; needs `a * b < p * 2^64`.
    #[inline(always)]
    fn mont_mul(&self, a: u64, b: u64) -> u64 {
        let t = u128::from(a) * u128::from(b);
        let lo = t as u64;
        let hi = (t >> 64) as u64;
        let m = lo.wrapping_mul(self.p_inv);
        let mp_hi = ((u128::from(m) * u128::from(self.p)) >> 64) as u64;
        // t - m p is divisible by 2^64 (equal low words, so no borrow), and lies in
        // (-p 2^64, p 2^64): its high word is in (-p, p).
        hi.wrapping_sub(mp_hi).wrapping_add(self.p)
    }

    /// `x` in `[0, p)`, from `x` in `[0, 2p)`.
    #[inline(always)]
    fn normalize(&self, x: u64) -> u64 {
        if x >= self.p {
            x - self.p
        } else {
            x
        }
    }

    /// The Montgomery form `x 2^64 mod p` of `x < p`, in `[0, p)`.
    fn to_mont(&self, x: u64) -> u64 {
        self.normalize(self.mont_mul(x, self.r2))
    }

    /// `x^e mod p` for `x` in Montgomery form, result in Montgomery form in `[0, p)`.
    fn pow_mont(&self, x: u64, mut e: u64) -> u64 {
        let mut acc = self.to_mont(1);
        let mut base = x;
        while e > 0 {
            if e & 1 == 1 {
                acc = self.normalize(self.mont_mul(acc, base));
            }
            base = self.normalize(self.mont_mul(base, base));
            e >>= 1;
        }
        acc
    }
}

/// The three primes: `c * 2^32 + 1` just below `2^62`, with a generator each.
static PRIMES: [Prime; 3] = [
    Prime::new(0x3fff_ffee_0000_0001, 3),
    Prime::new(0x3fff_ffb4_0000_0001, 19),
    Prime::new(0x3fff_ffa0_0000_0001, 3),
];

/// The largest transform length (`2^32`, the two-adicity of the primes).
const MAX_LOG_LEN: u32 = 32;

/// Twiddle factors in Montgomery form, for one prime and transforms of length up to
/// `len`: entries `[k, 2k)` hold `w_{2k}^j` for `j < k`, `w_{2k}` a primitive `2k`-th root
/// of unity (forward) or its inverse (inverse transform).
struct Twiddles {
    len: usize,
    forward: [Vec<u64>; 3],
    inverse: [Vec<u64>; 3],
}

impl Twiddles {
    fn new(len: usize) -> Twiddles {
        let table = |prime: &Prime, invert: bool| {
            let mut t = vec![0u64; len.max(2)];
            let order_log = len.trailing_zeros();
            let mut k = 1usize;
            let mut log = 1;
            while k < len {
                // primitive 2k-th root: g^((p-1)/2k)
                let g = prime.to_mont(prime.generator);
                let mut root = prime.pow_mont(g, (prime.p - 1) >> log);
                if invert {
                    root = prime.pow_mont(root, prime.p - 2);
                }
                let mut w = prime.to_mont(1);
                for slot in &mut t[k..2 * k] {
                    *slot = w;
                    w = prime.normalize(prime.mont_mul(w, root));
                }
                k *= 2;
                log += 1;
            }
            debug_assert!(order_log <= MAX_LOG_LEN);
            t
        };
        Twiddles {
            len,
            forward: [0, 1, 2].map(|i| table(&PRIMES[i], false)),
            inverse: [0, 1, 2].map(|i| table(&PRIMES[i], true)),
        }
    }
}

static TWIDDLES: Mutex<Option<Arc<Twiddles>>> = Mutex::new(None);

/// Twiddles for transforms of length at least `len` (a power of two).
fn twiddles(len: usize) -> Arc<Twiddles> {
    let mut cache = TWIDDLES.lock().unwrap_or_else(PoisonError::into_inner);
    match cache.as_ref() {
        Some(t) if t.len >= len => Arc::clone(t),
        _ => {
            let t = Arc::new(Twiddles::new(len));
            *cache = Some(Arc::clone(&t));
            t
        }
    }
}

/// Sub-transforms of at most this many entries (32 KiB) run stage by stage in the L1
/// cache; longer ones do their outer stage and recurse on the halves.
const CACHE_BLOCK: usize = 1 << 12;

/// In-place decimation-in-frequency transform: natural order in `[0, 2p)`, bit-reversed
/// order out in `[0, 2p)`.
fn forward(a: &mut [u64], prime: &Prime, tw: &[u64]) {
    let n = a.len();
    if n > CACHE_BLOCK {
        forward_stage(a, n / 2, prime, tw);
        let (lo, hi) = a.split_at_mut(n / 2);
        forward(lo, prime, tw);
        forward(hi, prime, tw);
        return;
    }
    let mut half = n / 2;
    while half >= 1 {
        forward_stage(a, half, prime, tw);
        half /= 2;
    }
}

/// One radix-2 stage on blocks of `2 half` entries: `butterfly(x, y, w)` on each pair of
/// entries `half` apart, `w` the twiddle of the pair's place in its block.
#[inline(always)]
fn stage(a: &mut [u64], half: usize, tw: &[u64], butterfly: impl Fn(&mut u64, &mut u64, u64)) {
    let w = &tw[half..2 * half];
    for block in a.chunks_exact_mut(2 * half) {
        let (x, y) = block.split_at_mut(half);
        for ((x, y), &w) in x.iter_mut().zip(y.iter_mut()).zip(w) {
            butterfly(x, y, w);
        }
    }
}

/// One radix-2 stage of [`forward`] on blocks of `2 half` entries.
#[inline(always)]
fn forward_stage(a: &mut [u64], half: usize, prime: &Prime, tw: &[u64]) {
    let two_p = 2 * prime.p;
    stage(a, half, tw, |x, y, w| {
        let (u, v) = (*x, *y);
        let s = u + v;
        *x = if s >= two_p { s - two_p } else { s };
        *y = prime.mont_mul(u + two_p - v, w);
    });
}

/// In-place decimation-in-time inverse transform (without the `1/n`): bit-reversed order
/// in, natural order out, values in `[0, 2p)`.
fn inverse(a: &mut [u64], prime: &Prime, tw: &[u64]) {
    let n = a.len();
    if n > CACHE_BLOCK {
        let (lo, hi) = a.split_at_mut(n / 2);
        inverse(lo, prime, tw);
        inverse(hi, prime, tw);
        inverse_stage(a, n / 2, prime, tw);
        return;
    }
    let mut half = 1;
    while half < n {
        inverse_stage(a, half, prime, tw);
        half *= 2;
    }
}

/// One radix-2 stage of [`inverse`] on blocks of `2 half` entries.
#[inline(always)]
fn inverse_stage(a: &mut [u64], half: usize, prime: &Prime, tw: &[u64]) {
    let two_p = 2 * prime.p;
    stage(a, half, tw, |x, y, w| {
        let u = *x;
        let t = prime.mont_mul(*y, w);
        let s = u + t;
        *x = if s >= two_p { s - two_p } else { s };
        let d = u + two_p - t;
        *y = if d >= two_p { d - two_p } else { d };
    });
}

/// The limbs of `x` reduced into `[0, 2p)` and folded onto `len` slots (limb `i` adds into
/// slot `i mod len`), so the slots stand for `x mod (2^(64 len) - 1)`.
fn load(x: &BigUint, prime: &Prime, len: usize) -> Vec<u64> {
    let two_p = 2 * prime.p;
    let reduce = |d: u64| {
        // d < 2^64 < 4p + 2p, so two conditional subtractions suffice.
        let d = if d >= two_p { d - two_p } else { d };
        if d >= two_p {
            d - two_p
        } else {
            d
        }
    };
    let mut v = vec![0u64; len];
    for (i, d) in x.iter_u64_digits().enumerate() {
        let slot = &mut v[i & (len - 1)];
        let s = *slot + reduce(d);
        *slot = if s >= two_p { s - two_p } else { s };
    }
    v
}

/// The number of 64-bit limbs of `x`.
pub(super) fn limbs(x: &BigUint) -> usize {
    x.iter_u64_digits().len()
}

/// The transform length for a product of `limbs` limbs: the next power of two.
pub(super) fn transform_len(limbs: usize) -> usize {
    let len = limbs.next_power_of_two().max(2);
    assert!(
        len.trailing_zeros() <= MAX_LOG_LEN,
        "a product of {limbs} limbs is too long for the transform"
    );
    len
}

/// A number's forward transforms modulo the three primes, at one length: computed once for
/// an operand that many products share.
pub(super) struct Transform {
    len: usize,
    residues: [Vec<u64>; 3],
}

impl Transform {
    /// The transform of `x mod (2^(64 len) - 1)`; `len` is a power of two.
    pub(super) fn new(x: &BigUint, len: usize) -> Transform {
        debug_assert!(len.is_power_of_two());
        let tw = twiddles(len);
        let residues = [0, 1, 2].map(|i| {
            let mut v = load(x, &PRIMES[i], len);
            forward(&mut v, &PRIMES[i], &tw.forward[i]);
            v
        });
        Transform { len, residues }
    }

    /// The transform length.
    pub(super) fn len(&self) -> usize {
        self.len
    }
}

/// `a b mod (2^(64 len) - 1)` for `b` transformed at length `len`, in `[0, 2^(64 len) - 1)`:
/// the whole product when `a` and `b` have at most `len` limbs together.
pub(super) fn mul_cyclic(a: &BigUint, b: &Transform) -> BigUint {
    let len = b.len;
    let tw = twiddles(len);
    let residues = [0, 1, 2].map(|i| {
        let prime = &PRIMES[i];
        let mut fa = load(a, prime, len);
        forward(&mut fa, prime, &tw.forward[i]);
        for (x, y) in fa.iter_mut().zip(&b.residues[i]) {
            *x = prime.mont_mul(*x, *y);
        }
        finish(fa, prime, &tw.inverse[i])
    });
    wrap(BigUint::from_slice(&crt(&residues, len)), len)
}

/// `a b`, by transforms; squares (two transforms fewer) when `a` and `b` are one object.
pub(super) fn mul(a: &BigUint, b: &BigUint) -> BigUint {
    let (la, lb) = (limbs(a), limbs(b));
    if la == 0 || lb == 0 {
        return BigUint::default();
    }
    let len = transform_len(la + lb);
    if !std::ptr::eq(a, b) {
        return mul_cyclic(a, &Transform::new(b, len));
    }
    let tw = twiddles(len);
    let residues = [0, 1, 2].map(|i| {
        let prime = &PRIMES[i];
        let mut fa = load(a, prime, len);
        forward(&mut fa, prime, &tw.forward[i]);
        for x in &mut fa {
            *x = prime.mont_mul(*x, *x);
        }
        finish(fa, prime, &tw.inverse[i])
    });
    BigUint::from_slice(&crt(&residues, len))
}

/// Inverse transform of pointwise products, scaled to the true residues in `[0, p)`.
fn finish(mut fa: Vec<u64>, prime: &Prime, inverse_twiddles: &[u64]) -> Vec<u64> {
    let len = fa.len();
    inverse(&mut fa, prime, inverse_twiddles);
    // Undo the 2^-64 of the pointwise products and the factor len of the inverse:
    // Montgomery-multiply by 2^128 / len.
    let len_inv = prime.pow_mont(prime.to_mont(len as u64 % prime.p), prime.p - 2);
    let scale = prime.normalize(prime.mont_mul(len_inv, prime.r2));
    for x in &mut fa {
        *x = prime.normalize(prime.mont_mul(*x, scale));
    }
    fa
}

/// `x mod (2^(64 len) - 1)`, in `[0, 2^(64 len) - 1)`.
pub(super) fn wrap(x: BigUint, len: usize) -> BigUint {
    let bits = 64 * len as u64;
    if x.bits() <= bits {
        return if x.bits() == bits && x.iter_u64_digits().all(|d| d == u64::MAX) {
            BigUint::default()
        } else {
            x
        };
    }
    let high = &x >> bits;
    let low = super::low_bits(&x, bits);
    wrap(low + high, len)
}

/// Constants of Garner's recombination, in Montgomery form where they multiply.
struct Garner {
    /// `p1^-1 mod p2`.
    inv_p1_mod_p2: u64,
    /// `(p1 p2)^-1 mod p3`.
    inv_p1p2_mod_p3: u64,
    /// `p1 mod p3`.
    p1_mod_p3: u64,
}

fn garner() -> Garner {
    let [p1, p2, p3] = [&PRIMES[0], &PRIMES[1], &PRIMES[2]];
    let inv = |x: u64, q: &Prime| q.pow_mont(q.to_mont(x % q.p), q.p - 2);
    let p1_mod_p3 = p3.to_mont(p1.p % p3.p);
    let p1p2 = ((u128::from(p1.p) * u128::from(p2.p)) % u128::from(p3.p)) as u64;
    Garner {
        inv_p1_mod_p2: inv(p1.p, p2),
        inv_p1p2_mod_p3: inv(p1p2, p3),
        p1_mod_p3,
    }
}

/// The product's limbs (as 32-bit digits for `BigUint::from_slice`) from its coefficients
/// modulo the three primes.
fn crt(residues: &[Vec<u64>], out_len: usize) -> Vec<u32> {
    let [p1, p2, p3] = [&PRIMES[0], &PRIMES[1], &PRIMES[2]];
    let g = garner();
    let p1p2 = u128::from(p1.p) * u128::from(p2.p);
    let mut out = Vec::with_capacity(2 * out_len + 2);
    // 192-bit carry (c0 + c1 2^64 + c2 2^128).
    let (mut c0, mut c1, mut c2) = (0u64, 0u64, 0u64);
    let triples = residues[0][..out_len]
        .iter()
        .zip(&residues[1][..out_len])
        .zip(&residues[2][..out_len]);
    for ((&r1, &r2), &r3) in triples {
        // t2 = (r2 - r1) / p1 mod p2
        let r1_2 = if r1 >= p2.p { r1 - p2.p } else { r1 };
        let t2 = p2.normalize(p2.mont_mul(r2 + p2.p - r1_2, g.inv_p1_mod_p2));
        // t3 = (r3 - r1 - p1 t2) / (p1 p2) mod p3
        let r1_3 = if r1 >= p3.p { r1 - p3.p } else { r1 };
        let p1t2 = p3.normalize(p3.mont_mul(t2, g.p1_mod_p3));
        let diff = {
            let a = r3 + 2 * p3.p - r1_3 - p1t2; // in (0, 3p)
            let a = if a >= p3.p { a - p3.p } else { a };
            if a >= p3.p {
                a - p3.p
            } else {
                a
            }
        };
        let t3 = p3.normalize(p3.mont_mul(diff, g.inv_p1p2_mod_p3));
        // x = r1 + p1 t2 + p1 p2 t3 < 2^186
        let a = u128::from(r1) + u128::from(p1.p) * u128::from(t2); // < 2^125
        let lo = (p1p2 & u128::from(u64::MAX)) * u128::from(t3);
        let hi = (p1p2 >> 64) * u128::from(t3);
        // x = a + lo + hi 2^64
        let (s, carry1) = a.overflowing_add(lo);
        let x0 = s as u64;
        let mid = (s >> 64) + (hi & u128::from(u64::MAX)); // < 2^65
        let x1 = mid as u64;
        let x2 = ((mid >> 64) + (hi >> 64) + (u128::from(carry1) << 64)) as u64;
        // carry += x
        let (s0, k0) = c0.overflowing_add(x0);
        let (s1, k1a) = c1.overflowing_add(x1);
        let (s1, k1b) = s1.overflowing_add(u64::from(k0));
        let s2 = c2 + x2 + u64::from(k1a) + u64::from(k1b);
        out.push(s0 as u32);
        out.push((s0 >> 32) as u32);
        (c0, c1, c2) = (s1, s2, 0);
    }
    for c in [c0, c1, c2] {
        out.push(c as u32);
        out.push((c >> 32) as u32);
    }
    out
}
