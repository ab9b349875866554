"""Output files of the chart scripts, written atomically: each goes to a temporary name in
its own folder and is renamed over the target only when complete, so a full disk or a
crash never leaves a truncated PNG or table at the final name, and no temporary behind.
run() turns an OSError into one line naming the file and the cause (on a full disk:
"No space left on device (ENOSPC: the disk is full)"), exit status 1."""
import errno
import os
import sys
import tempfile


def _umask():
    old = os.umask(0)
    os.umask(old)
    return old


def replace(path, write):
    """Calls write(binary file object) for a temporary file beside `path`, then renames it onto `path`."""
    folder, base = os.path.split(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{base}.", suffix=".tmp", dir=folder or ".")
    try:
        try:
            with os.fdopen(fd, "wb") as f:
                write(f)
                f.flush()
                os.fsync(f.fileno())
            os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0600; outputs follow the umask
            os.replace(tmp, path)
        except OSError as e:
            raise OSError(e.errno, e.strerror, path) from e
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def write_text(path, text):
    replace(path, lambda f: f.write(text.encode()))


def save_figure(fig, path, **kwargs):
    replace(path, lambda f: fig.savefig(f, format="png", **kwargs))


def pyplot():
    """matplotlib.pyplot on the Agg backend, or exit naming the missing package."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        sys.exit(f"{os.path.basename(sys.argv[0])}: cannot import matplotlib ({e}): is python3-matplotlib installed?")
    return plt


def run(main):
    try:
        return main()
    except OSError as e:
        hint = ""
        if e.errno == errno.ENOSPC:
            hint = " (ENOSPC: the disk is full)"
        elif e.errno == errno.EDQUOT:
            hint = " (EDQUOT: over the disk quota)"
        where = f"{e.filename}: " if e.filename else ""
        sys.exit(f"{os.path.basename(sys.argv[0])}: {where}{e.strerror}{hint}")
