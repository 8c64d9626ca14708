"""Replacing generated/ atomically, recovering from an interrupted replacement, and the lock
that serialises writers. No SymPy here: `lambda-bezier derive` writes with it and the runtime's
importer recovers with it.

The new tree is written and flushed in a sibling `.generated.new-*` directory, then swapped in
with one rename(2) RENAME_EXCHANGE (Linux): at every instant `generated/` is either the old tree
or the new one. Where the exchange is not available (another OS, a file system without it) two
renames are used, old -> `.generated.old`, new -> `generated/`; a crash between them leaves
no generated/ but a `.generated.old` that `recover` (run by the next derive and by the
importer) puts back. Debris of an interrupted run (`.generated.new-*`, `.generated.old`) is
removed by the next one. Writers hold an exclusive flock(2) on `.generated.lock` next to the
directory (removed again on release), so two runs at once wait for each other instead of
racing.
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import sys
import tempfile
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path

Say = Callable[[str], None]


def _quiet(msg: str) -> None:
    pass


def new_prefix(directory: Path) -> str:
    return f".{directory.name}.new-"


def backup_path(directory: Path) -> Path:
    return directory.parent / f".{directory.name}.old"


def lock_path(directory: Path) -> Path:
    return directory.parent / f".{directory.name}.lock"


@contextlib.contextmanager
def locked(directory: Path, say: Say = _quiet, *, required: bool = True) -> Iterator[None]:
    """An exclusive lock on `directory`'s lock file for the duration; when another process
    holds it, say so and wait. The lock file is removed on release, so nothing is left in the
    checkout: a waiter that then finds its file unlinked (or replaced) tries again. With
    required=False a lock file that cannot be created (a read-only installation) means no
    locking instead of an error."""
    try:
        import fcntl
    except ImportError:  # no flock on this platform: unserialised
        yield
        return
    path = lock_path(directory)
    while True:
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError:
            if required:
                raise
            yield
            return
        try:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                say(
                    f"another `lambda-bezier derive` is writing {directory} (it holds "
                    f"{path.name}); waiting for it to finish"
                )
                fcntl.flock(fd, fcntl.LOCK_EX)
            try:
                current = os.stat(path).st_ino
            except FileNotFoundError:
                current = None
            if current != os.fstat(fd).st_ino:  # released and unlinked while we waited
                continue
            try:
                yield
            finally:
                with contextlib.suppress(OSError):
                    os.unlink(path)  # still holding the lock: nobody else owns this file
            return
        finally:
            os.close(fd)


def recover(directory: Path) -> list[str]:
    """Undo what an interrupted replacement left behind (call it holding the lock): put a
    lone backup back in place, then remove backups and half-written new trees. Returns one
    message per action."""
    done = []
    backup = backup_path(directory)
    if not directory.exists() and backup.is_dir():
        os.replace(backup, directory)
        done.append(
            f"restored {directory} from {backup.name} (an earlier `lambda-bezier derive` was "
            "interrupted between its two renames)"
        )
    elif backup.exists():
        shutil.rmtree(backup)
        done.append(f"removed {backup.name}, left by an interrupted `lambda-bezier derive`")
    for debris in sorted(directory.parent.glob(new_prefix(directory) + "*")):
        shutil.rmtree(debris)
        done.append(f"removed {debris.name}, left by an interrupted `lambda-bezier derive`")
    return done


def _exchange(a: Path, b: Path) -> bool:
    """Swap two directories in one atomic step (renameat2 RENAME_EXCHANGE); False where the
    system or file system does not offer it."""
    if not sys.platform.startswith("linux"):
        return False
    import ctypes

    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):  # a libc without the wrapper (glibc < 2.28, musl)
        return False
    renameat2.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p]
    renameat2.argtypes += [ctypes.c_uint]
    at_fdcwd, rename_exchange = -100, 2
    if renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(b))


def _fsync_dir(path: Path) -> None:
    with contextlib.suppress(OSError):  # not every system can open a directory
        fd = os.open(path, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def replace_tree(files: Mapping[str, str], directory: Path, say: Say = _quiet) -> None:
    """Replace `directory` by exactly `files` (relative path -> text), atomically, under the
    lock, after recovering from any interrupted earlier run. The directory gets the mode a
    newly made directory gets (0755 under the usual umask), not mkdtemp's 0700. An OSError
    (e.g. PermissionError) leaves `directory` as it was."""
    directory = Path(directory)
    parent = directory.parent
    with locked(directory, say):
        for msg in recover(directory):
            say(msg)
        if directory.exists() and not os.access(directory, os.W_OK):
            raise PermissionError(errno.EACCES, "the directory is read-only", str(directory))
        tmp = Path(tempfile.mkdtemp(prefix=new_prefix(directory), dir=parent))
        backup = backup_path(directory)
        exchanged = False
        try:
            os.chmod(tmp, 0o777 & ~_umask())
            for name, text in files.items():
                path = tmp / name
                path.parent.mkdir(parents=True, exist_ok=True)
                with open(path, "w", encoding="utf-8", newline="\n") as fh:
                    fh.write(text)
                    fh.flush()
                    os.fsync(fh.fileno())
            _fsync_dir(tmp)
            if directory.exists():
                exchanged = _exchange(tmp, directory)
                if not exchanged:
                    os.replace(directory, backup)
                    os.replace(tmp, directory)
            else:
                os.replace(tmp, directory)
            _fsync_dir(parent)
        except BaseException:
            if not exchanged:
                shutil.rmtree(tmp, ignore_errors=True)
                if backup.exists() and not directory.exists():
                    os.replace(backup, directory)
            raise
        # the old tree: in tmp after an exchange, in the backup after two renames
        shutil.rmtree(tmp if exchanged else backup, ignore_errors=True)


def recover_for_import(package_dir: Path) -> None:
    """Called by the importer when lambda_bezier._generated cannot be found: restore it from
    the backup an interrupted derive left, or raise an ImportError that says what happened."""
    candidates = [package_dir / "_generated"]
    checkout = package_dir.parent.parent  # src/lambda_bezier -> the checkout
    if (checkout / "derive" / "__init__.py").is_file():
        candidates.insert(0, checkout / "generated")
    for directory in candidates:
        if directory.exists() or not backup_path(directory).is_dir():
            continue
        try:
            with locked(directory, required=False):
                recover(directory)
        except OSError as exc:
            raise ImportError(
                f"lambda_bezier's generated modules are missing: {directory} was moved to "
                f"{backup_path(directory).name} by an interrupted `lambda-bezier derive`, and "
                f"moving it back failed ({exc.strerror}); rename it back or run "
                "`lambda-bezier derive`"
            ) from None
        return
    raise ImportError(
        "lambda_bezier's generated modules are missing (looked for "
        f"{' and '.join(map(str, candidates))}); in a checkout restore them with "
        "`git checkout generated/` or `lambda-bezier derive`, otherwise reinstall lambda-bezier"
    )
