"""Reading the files a user names, and writing output files, safely.

`read_text` never blocks and never reads without bound: a named pipe, a device (a symlink
to /dev/zero), a folder or a file beyond a size limit is an input error naming the file,
and so is every operating-system error (name too long, permission denied, ...).

`write_atomic` is the one way pycram writes a file: into a temporary file in the same
folder, then renamed over the target, so that a reader sees the old file or the new one,
never a part of it, and two writers leave one of their files whole.
"""
from __future__ import annotations

import contextlib
import errno
import os
import stat
import tempfile
from pathlib import Path

from .errors import InputError, Location
from .limits import size_text

_KINDS = {stat.S_IFIFO: "a named pipe", stat.S_IFCHR: "a character device", stat.S_IFBLK: "a block device",
          stat.S_IFSOCK: "a socket", stat.S_IFDIR: "a folder"}

_REASONS = {
    errno.ENOENT: "file not found",
    errno.ENAMETOOLONG: "file name too long",
    errno.EACCES: "permission denied",
    errno.EPERM: "permission denied",
    errno.EISDIR: "is a folder, not a file",
    errno.ENOTDIR: "a part of the path is not a folder",
    errno.ELOOP: "too many levels of symbolic links",
    errno.EROFS: "read-only file system",
    errno.ENOSPC: "no space left on the device",
    errno.EDQUOT: "disk quota exceeded",
    errno.EXDEV: "cannot rename across file systems",
}


def reason(exc: OSError) -> str:
    """A short, human reason for an operating-system error."""
    if exc.errno in _REASONS:
        return _REASONS[exc.errno]
    return (exc.strerror or type(exc).__name__).lower()


def kind_of(mode: int) -> str:
    """'a named pipe', 'a folder', ... for a file's mode; 'a special file' when unknown."""
    return _KINDS.get(stat.S_IFMT(mode), "a special file")


def probe(path: str | Path) -> str | None:
    """None when `path` is a regular file (symlinks followed); otherwise why it is not one, for a message:
    'not found', 'file name too long', 'it is a named pipe, not a regular file', ..."""
    try:
        info = os.stat(os.fspath(path))
    except ValueError:
        return "the file name contains a NUL character"
    except OSError as exc:
        return "not found" if exc.errno in (errno.ENOENT, errno.ENOTDIR) else reason(exc)
    if not stat.S_ISREG(info.st_mode):
        return f"it is {kind_of(info.st_mode)}, not a regular file"
    return None


def read_bytes(path: str | Path, limit: int, what: str = "file", key: str | None = None) -> bytes:
    """The bytes of a regular file of at most `limit` bytes; every problem is an InputError at the file."""
    where = Location(str(path))
    try:
        fd = os.open(os.fspath(path), os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0))
    except ValueError:  # an embedded NUL character
        raise InputError(f"cannot read {what}: the file name contains a NUL character", where, key=key) from None
    except OSError as exc:
        message = f"{what} not found" if exc.errno == errno.ENOENT else f"cannot read {what}: {reason(exc)}"
        raise InputError(message, where, key=key) from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise InputError(f"cannot read {what}: it is {kind_of(info.st_mode)}, not a regular file", where, key=key)
        if info.st_size > limit:
            raise InputError(f"{what} too large: {size_text(info.st_size)} (the limit is {size_text(limit)})",
                             where, key=key)
        chunks: list[bytes] = []
        total = 0
        while True:  # files whose size says 0 (/proc) are read up to the limit too
            chunk = os.read(fd, min(1 << 20, limit + 1 - total))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
            if total > limit:
                raise InputError(f"{what} too large: more than {size_text(limit)}", where, key=key)
        return b"".join(chunks)
    except OSError as exc:
        raise InputError(f"cannot read {what}: {reason(exc)}", where, key=key) from None
    finally:
        os.close(fd)


def read_text(path: str | Path, limit: int, what: str = "file", key: str | None = None) -> str:
    """The UTF-8 text of a regular file (see `read_bytes`); bytes that are not UTF-8 are reported at their line."""
    data = read_bytes(path, limit, what, key)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        column = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise InputError(f"not UTF-8 text (byte 0x{data[exc.start]:02x})", Location(str(path), line, column),
                         key=key) from None


def check_writable(path: str | Path, key: str | None = None) -> None:
    """Raise an InputError now, before any work, when `path` cannot be written as an output file."""
    where = Location(str(path))
    target = Path(path)
    try:
        info = os.stat(target)
    except FileNotFoundError:
        info = None
    except OSError as exc:
        if exc.errno != errno.ENOENT:
            raise InputError(f"cannot write: {reason(exc)}", where, key=key) from None
        info = None
    except ValueError:
        raise InputError("cannot write: the file name contains a NUL character", where, key=key) from None
    if info is not None and not stat.S_ISREG(info.st_mode):
        raise InputError(f"cannot write: it is {kind_of(info.st_mode)}, not a regular file", where, key=key)
    if len(target.name.encode()) > 255:
        raise InputError("cannot write: file name too long", where, key=key)
    try:  # the real test: a temporary file in its folder (which must exist), as writing will make
        folder = _real(target).parent
        if not folder.is_dir():
            raise InputError(f"cannot write: folder '{folder}' does not exist", where, key=key)
        fd, temporary = tempfile.mkstemp(dir=folder, prefix=".pycram-", suffix=".tmp")
        os.close(fd)
        os.unlink(temporary)
    except OSError as exc:
        why = f"files cannot be made in folder '{folder}'" if exc.errno == errno.ENOENT else reason(exc)
        raise InputError(f"cannot write: {why}", where, key=key) from None


def write_atomic(path: str | Path, data: str | bytes, key: str | None = None) -> None:
    """Write `data` to `path` through a temporary file in the same folder, renamed over it.

    Missing folders are made. A symlink is followed (its target is replaced). Every
    operating-system problem is an InputError at the path.
    """
    where = Location(str(path))
    payload = data.encode("utf-8") if isinstance(data, str) else data
    try:
        target = _real(Path(path))
        try:
            info = os.stat(target)
        except FileNotFoundError:
            info = None
        if info is not None and not stat.S_ISREG(info.st_mode):
            raise InputError(f"cannot write: it is {kind_of(info.st_mode)}, not a regular file", where, key=key)
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, temporary = tempfile.mkstemp(dir=target.parent, prefix=".pycram-", suffix=".tmp")
    except ValueError:
        raise InputError("cannot write: the file name contains a NUL character", where, key=key) from None
    except OSError as exc:
        raise InputError(f"cannot write: {reason(exc)}", where, key=key) from None
    try:
        with os.fdopen(fd, "wb") as stream:
            stream.write(payload)
        os.chmod(temporary, info.st_mode & 0o7777 if info is not None else 0o666 & ~_umask())
        os.replace(temporary, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        if isinstance(exc, OSError):
            raise InputError(f"cannot write: {reason(exc)}", where, key=key) from None
        raise


def _real(path: Path) -> Path:
    """A symlink's final target (so that writing replaces the file, not the link); other paths as they are."""
    try:
        return Path(os.path.realpath(path)) if path.is_symlink() else path
    except OSError:
        return path


_UMASK: int | None = None


def _umask() -> int:
    global _UMASK
    if _UMASK is None:
        current = os.umask(0o022)
        os.umask(current)
        _UMASK = current
    return _UMASK
