//! Writing a long run of lines or records in chunks: each chunk formatted into a buffer of
//! its own, the buffers written in order. With threads, a window of chunks is formatted in
//! parallel while the calling thread writes the window before it, so at most two windows
//! of buffers are alive (a few megabytes, reused from window to window, never the file).
//! What is written does not depend on the threads: a chunk's bytes depend on its items only.

use std::io::Write;
use std::ops::Range;

use rayon::prelude::*;

/// Chunks per thread in a window: enough for rayon to balance uneven chunks.
const CHUNKS_PER_THREAD: usize = 4;

/// Below this many items a section is formatted on the calling thread.
const PARALLEL_MIN_ITEMS: usize = 1 << 15;

/// Where the formatting runs.
enum Mode {
    /// Everything on the calling thread.
    Calling,
    /// rayon's current pool (the one the call runs in, else the global one).
    Current,
    /// A pool of its own.
    Pool(rayon::ThreadPool),
}

/// A writer of chunked sections into `W`.
pub(crate) struct ChunkWriter<W> {
    out: W,
    mode: Mode,
    /// The buffers being formatted, and those of the window before (being written).
    front: Vec<Vec<u8>>,
    back: Vec<Vec<u8>>,
}

impl<W: Write> ChunkWriter<W> {
    /// A writer into `out` with `threads`: 1 formats on the calling thread, 0 in rayon's
    /// current pool, `n >= 2` in a pool of `n` threads, built when `items` (what the writer
    /// will format, all sections together) are enough to gain from it.
    ///
    /// # Errors
    ///
    /// [`std::io::ErrorKind::Other`] when the pool cannot be built.
    pub(crate) fn new(out: W, threads: usize, items: usize) -> std::io::Result<ChunkWriter<W>> {
        let mode = match threads {
            _ if items < PARALLEL_MIN_ITEMS => Mode::Calling,
            1 => Mode::Calling,
            0 if rayon::current_num_threads() <= 1 => Mode::Calling,
            0 => Mode::Current,
            n => Mode::Pool(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .map_err(std::io::Error::other)?,
            ),
        };
        Ok(ChunkWriter {
            out,
            mode,
            front: Vec::new(),
            back: Vec::new(),
        })
    }

    /// The threads formatting (1 on the calling thread).
    fn threads(&self) -> usize {
        match &self.mode {
            Mode::Calling => 1,
            Mode::Current => rayon::current_num_threads(),
            Mode::Pool(pool) => pool.current_num_threads(),
        }
    }

    /// Writes `bytes` as they are.
    pub(crate) fn write_all(&mut self, bytes: &[u8]) -> std::io::Result<()> {
        self.out.write_all(bytes)
    }

    /// Writes items `0..n`: `format(range, buffer)` appends the bytes of the items of `range`
    /// to `buffer`, called on consecutive ranges of `chunk` items (the last may be shorter).
    ///
    /// # Errors
    ///
    /// Any error of the writer.
    pub(crate) fn section<F>(&mut self, n: usize, chunk: usize, format: F) -> std::io::Result<()>
    where
        F: Fn(Range<usize>, &mut Vec<u8>) + Sync,
    {
        let chunk = chunk.max(1);
        let threads = self.threads();
        if threads <= 1 || n < PARALLEL_MIN_ITEMS {
            if self.front.is_empty() {
                self.front.push(Vec::new());
            }
            let buffer = &mut self.front[0];
            for start in (0..n).step_by(chunk) {
                buffer.clear();
                format(start..(start + chunk).min(n), buffer);
                self.out.write_all(buffer)?;
            }
            return Ok(());
        }
        let per_window = CHUNKS_PER_THREAD * threads;
        let Self {
            out,
            mode,
            front,
            back,
        } = self;
        let pool = match mode {
            Mode::Pool(pool) => Some(&*pool),
            Mode::Calling | Mode::Current => None,
        };
        front.resize_with(per_window, Vec::new);
        back.resize_with(per_window, Vec::new);
        let window_items = per_window * chunk;
        let windows = n.div_ceil(window_items);
        // Window `k` is formatted into `front` while window `k - 1`, in `back`, is written.
        for k in 0..=windows {
            let format = &format;
            let buffers = &mut *front;
            let fill = move |_: &rayon::Scope<'_>| {
                buffers.par_iter_mut().enumerate().for_each(|(i, buffer)| {
                    buffer.clear();
                    let start = k * window_items + i * chunk;
                    if k < windows && start < n {
                        format(start..(start + chunk).min(n), buffer);
                    }
                });
            };
            // Empty at `k == 0`: the last window of a section formats nothing.
            let previous = &*back;
            let out = &mut *out;
            overlap(pool, fill, || {
                previous.iter().try_for_each(|b| out.write_all(b))
            })?;
            std::mem::swap(front, back);
        }
        Ok(())
    }

    /// Flushes the writer.
    ///
    /// # Errors
    ///
    /// Any error of the writer.
    pub(crate) fn flush(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}

/// Runs `fill` in `pool` (rayon's current pool without one) while `write` runs on the
/// calling thread; returns what `write` returns once both are done.
fn overlap<'scope, R>(
    pool: Option<&rayon::ThreadPool>,
    fill: impl FnOnce(&rayon::Scope<'scope>) + Send + 'scope,
    write: impl FnOnce() -> R,
) -> R {
    match pool {
        Some(pool) => pool.in_place_scope(|s| {
            s.spawn(fill);
            write()
        }),
        None => rayon::in_place_scope(|s| {
            s.spawn(fill);
            write()
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same bytes for every thread count, chunk size and section length, the sections in
    /// order.
    #[test]
    fn the_same_bytes_whatever_the_threads() {
        let text = |threads: usize, chunk: usize, n: usize| {
            let mut out = Vec::new();
            let mut writer = ChunkWriter::new(&mut out, threads, n + 2).expect("a pool");
            writer.write_all(b"head\n").expect("written");
            writer
                .section(n, chunk, |range, buffer| {
                    for i in range {
                        buffer.extend_from_slice(format!("{i} {}\n", i * i).as_bytes());
                    }
                })
                .expect("written");
            writer
                .section(2, chunk, |range, buffer| {
                    for i in range {
                        buffer.extend_from_slice(format!("<{i}>").as_bytes());
                    }
                })
                .expect("written");
            writer.flush().expect("flushed");
            out
        };
        for n in [0, 1, 5, PARALLEL_MIN_ITEMS - 1, PARALLEL_MIN_ITEMS, 100_003] {
            let one = text(1, 1000, n);
            let mut expected = b"head\n".to_vec();
            for i in 0..n {
                expected.extend_from_slice(format!("{i} {}\n", i * i).as_bytes());
            }
            expected.extend_from_slice(b"<0><1>");
            assert_eq!(one, expected, "{n}");
            for (threads, chunk) in [(2, 1000), (2, 7), (3, 4096), (0, 1 << 20), (2, 0)] {
                assert_eq!(text(threads, chunk, n), one, "{n} {threads} {chunk}");
            }
        }
    }

    /// An error of the writer is returned, after the formatting running at the time ends.
    #[test]
    fn a_failing_writer_is_an_error() {
        struct Failing(usize);
        impl Write for Failing {
            fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
                if self.0 == 0 {
                    return Err(std::io::Error::other("full"));
                }
                self.0 -= 1;
                Ok(buf.len())
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        for threads in [1, 2] {
            let mut writer = ChunkWriter::new(Failing(3), threads, 1 << 20).expect("a pool");
            let err = writer
                .section(1 << 20, 1000, |range, buffer| {
                    buffer.extend(range.map(|i| i as u8));
                })
                .unwrap_err();
            assert_eq!(err.to_string(), "full");
        }
    }
}
