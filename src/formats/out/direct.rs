//! Writing big output files past the page cache (`O_DIRECT` on Linux).
//!
//! A big kit writes gigabytes of cutting files. Written the usual way,
//! every byte is copied into the kernel's page cache first, into pages
//! the kernel must find and zero; on a virtual machine whose memory the
//! host hands back and forth, that copy cost more CPU than formatting the
//! files (2.5 s of system time per 1.5 GB here, against 0.2 s written
//! directly). So files of at least [`DIRECT_MIN_BYTES`] are written with
//! `O_DIRECT` where the file system takes it: whole 4 KiB blocks from an
//! aligned buffer, the last partial block through an ordinary handle.
//! Where it does not (tmpfs, some network file systems, other systems),
//! or a direct write is refused, the file is written the ordinary way:
//! the bytes on disk are the same either way.

use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::Path;

/// Files smaller than this are written the ordinary way.
pub const DIRECT_MIN_BYTES: usize = 256 * 1024;

/// Block size direct writes are aligned to (offset, length and memory):
/// the largest logical block size of common disks.
const BLOCK: usize = 4096;

/// Bytes handed to the kernel per direct write.
const CHUNK: usize = 1 << 20;

/// Write `bytes` to `path` (created or truncated), directly when it is big
/// enough and the file system allows it.
pub fn write_file(path: &Path, bytes: &[u8]) -> io::Result<()> {
    if bytes.len() >= DIRECT_MIN_BYTES {
        if let Some(file) = open_direct(path) {
            let mut w = DirectWriter::new(file, path);
            w.write_all(bytes)?;
            return w.finish();
        }
    }
    std::fs::write(path, bytes)
}

/// A writer into a new file at `path`: direct when the file system
/// allows it, else buffered. Call [`Writer::finish`] at the end.
pub enum Writer<'a> {
    /// Whole blocks directly, the tail at the end.
    Direct(DirectWriter<'a>),
    /// The ordinary way.
    Buffered(io::BufWriter<File>),
}

impl<'a> Writer<'a> {
    /// Create (or truncate) `path`.
    pub fn create(path: &'a Path) -> io::Result<Writer<'a>> {
        match open_direct(path) {
            Some(file) => Ok(Writer::Direct(DirectWriter::new(file, path))),
            None => Ok(Writer::Buffered(io::BufWriter::with_capacity(
                CHUNK,
                File::create(path)?,
            ))),
        }
    }

    /// Whether it writes past the page cache.
    pub fn is_direct(&self) -> bool {
        matches!(self, Writer::Direct(_))
    }

    /// Write what is left and close the file.
    pub fn finish(self) -> io::Result<()> {
        match self {
            Writer::Direct(w) => w.finish(),
            Writer::Buffered(mut w) => w.flush(),
        }
    }
}

impl Write for Writer<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Writer::Direct(w) => w.write(buf),
            Writer::Buffered(w) => w.write(buf),
        }
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        match self {
            Writer::Direct(w) => w.write_all(buf),
            Writer::Buffered(w) => w.write_all(buf),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        // Direct writes go out block by block; the tail waits for `finish`.
        match self {
            Writer::Direct(_) => Ok(()),
            Writer::Buffered(w) => w.flush(),
        }
    }
}

/// `path` created (or truncated) for direct writes, or `None` where the
/// file system (or the platform) does not take them.
fn open_direct(path: &Path) -> Option<File> {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::OpenOptionsExt;
        OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(true)
            .custom_flags(libc::O_DIRECT)
            .open(path)
            .ok()
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = path;
        None
    }
}

/// Whole blocks written directly from an aligned buffer; the bytes past
/// the last whole block go through an ordinary handle at the end. If the
/// kernel refuses a direct write, the rest is written the ordinary way.
pub struct DirectWriter<'a> {
    file: File,
    path: &'a Path,
    /// `CHUNK + BLOCK` bytes, of which `[start..start + CHUNK]` is aligned.
    buf: Vec<u8>,
    start: usize,
    /// Bytes waiting in the aligned window.
    len: usize,
    /// Bytes in the file before the window.
    written: u64,
    /// Set once a direct write was refused: everything after goes through
    /// an ordinary handle.
    fallback: Option<File>,
}

thread_local! {
    /// The aligned buffer a thread's last direct writer left: a kit's
    /// thousands of files reuse it rather than each zeroing a new MiB.
    static SPARE: std::cell::RefCell<Vec<u8>> = const { std::cell::RefCell::new(Vec::new()) };
}

impl<'a> DirectWriter<'a> {
    fn new(file: File, path: &'a Path) -> DirectWriter<'a> {
        let mut buf = SPARE.with(|s| std::mem::take(&mut *s.borrow_mut()));
        if buf.len() != CHUNK + BLOCK {
            buf = vec![0u8; CHUNK + BLOCK];
        }
        // `align_offset` may decline (it never does for u8 in practice);
        // then writes fall back at the first refusal.
        let start = buf.as_ptr().align_offset(BLOCK).min(BLOCK);
        DirectWriter {
            file,
            path,
            buf,
            start,
            len: 0,
            written: 0,
            fallback: None,
        }
    }

    /// Write the aligned window's first `n` bytes (a multiple of BLOCK).
    fn write_blocks(&mut self, n: usize) -> io::Result<()> {
        let window = &self.buf[self.start..self.start + n];
        if self.fallback.is_none() {
            match self.file.write_all(window) {
                Ok(()) => {
                    self.written += n as u64;
                    return Ok(());
                }
                Err(e) if e.raw_os_error() == Some(libc_einval()) => {
                    // Refused (alignment this file system does not take):
                    // this window and the rest the ordinary way, after
                    // what was written before it.
                    let f = OpenOptions::new().write(true).open(self.path)?;
                    f.set_len(self.written)?;
                    self.fallback = Some(f);
                }
                Err(e) => return Err(e),
            }
        }
        if let Some(f) = &mut self.fallback {
            use std::io::Seek;
            f.seek(io::SeekFrom::End(0))?;
            f.write_all(window)?;
        }
        self.written += n as u64;
        Ok(())
    }

    /// Write what is left (the tail through an ordinary handle) and close.
    pub fn finish(mut self) -> io::Result<()> {
        let r = self.finish_writes();
        SPARE.with(|s| *s.borrow_mut() = std::mem::take(&mut self.buf));
        r
    }

    fn finish_writes(&mut self) -> io::Result<()> {
        let whole = self.len / BLOCK * BLOCK;
        if whole > 0 {
            self.write_blocks(whole)?;
        }
        let tail = self.start + whole..self.start + self.len;
        if !tail.is_empty() {
            let mut f = match self.fallback.take() {
                Some(f) => f,
                None => OpenOptions::new().append(true).open(self.path)?,
            };
            use std::io::Seek;
            f.seek(io::SeekFrom::End(0))?;
            f.write_all(&self.buf[tail])?;
        }
        Ok(())
    }
}

impl Write for DirectWriter<'_> {
    fn write(&mut self, data: &[u8]) -> io::Result<usize> {
        let n = data.len().min(CHUNK - self.len);
        let at = self.start + self.len;
        self.buf[at..at + n].copy_from_slice(&data[..n]);
        self.len += n;
        if self.len == CHUNK {
            self.write_blocks(CHUNK)?;
            self.len = 0;
        }
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// EINVAL, what Linux answers a direct write it cannot align.
fn libc_einval() -> i32 {
    #[cfg(target_os = "linux")]
    {
        libc::EINVAL
    }
    #[cfg(not(target_os = "linux"))]
    {
        22
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bytes that are not the same from block to block.
    fn pattern(n: usize) -> Vec<u8> {
        (0..n).map(|i| (i * 7 + i / 4093) as u8).collect()
    }

    #[test]
    fn every_size_reads_back_the_same_bytes() {
        // On the disk the project is on (a tmpfs /tmp would only test the
        // ordinary way).
        let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("target")
            .join(format!("lamella-direct-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let probe_path = dir.join("probe");
        let probe = Writer::create(&probe_path).unwrap();
        if !probe.is_direct() {
            eprintln!("no direct writes on this file system: testing the ordinary way only");
        }
        probe.finish().unwrap();
        // Below the threshold, exactly blocks, a chunk and a bit, several
        // chunks with a tail; and the same through the streaming writer in
        // odd pieces.
        for n in [
            0,
            1,
            DIRECT_MIN_BYTES - 1,
            DIRECT_MIN_BYTES,
            64 * BLOCK,
            CHUNK + 1,
            3 * CHUNK + 4095,
            3 * CHUNK + 4097,
        ] {
            let data = pattern(n);
            let p = dir.join(format!("f{n}"));
            write_file(&p, &data).unwrap();
            assert_eq!(std::fs::read(&p).unwrap(), data, "write_file, {n} bytes");
            let q = dir.join(format!("g{n}"));
            let mut w = Writer::create(&q).unwrap();
            for piece in data.chunks(12_345) {
                w.write_all(piece).unwrap();
            }
            w.finish().unwrap();
            assert_eq!(std::fs::read(&q).unwrap(), data, "Writer, {n} bytes");
        }
        // Rewriting a longer file leaves no old bytes behind.
        let p = dir.join("shrink");
        write_file(&p, &pattern(2 * CHUNK)).unwrap();
        write_file(&p, &pattern(CHUNK + 5)).unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), pattern(CHUNK + 5));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
