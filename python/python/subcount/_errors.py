"""The exceptions and the warning category of subcount (a public contract).

Each error class matches one exit code of the ``subcount`` command line, and carries its
message:

- ``MismatchError`` (exit 1): a real subdivision disagreed with the prediction (a bug).
- ``UsageError`` (exit 2): the request is wrong (an unknown scheme, options that do not go
  together, a scheme without the mode asked for); also a ``ValueError``.
- ``InputError`` (exit 3): a bad mesh file or array, or a scheme that does not apply to the
  mesh; also a ``ValueError``.
- ``ResourceError`` (exit 4): a resource guard refused the work (it would not fit the memory
  available); also a ``MemoryError``.

``Warning`` is the category of the command line's notes (``warnings.warn(note,
subcount.Warning)``).
"""

import builtins
import typing


class Error(Exception):
    """Any error of subcount (an internal error, a bug, is raised as this class itself)."""


class UsageError(Error, ValueError):
    """The request is wrong (the command line's exit code 2)."""


class InputError(Error, ValueError):
    """A bad mesh file or array, or a scheme that does not apply (exit code 3)."""


class ResourceError(Error, MemoryError):
    """A resource guard refused the work (exit code 4)."""


class MismatchError(Error):
    """A real subdivision disagreed with the prediction (exit code 1).

    ``report`` holds ``verify``'s levels (one dict per level, the differing one included).
    """

    report: "typing.Optional[typing.List[typing.Dict[str, typing.Any]]]" = None


class Warning(builtins.UserWarning):  # noqa: A001 - the public name
    """A note of subcount (a tag not read, an option a scheme does not apply)."""


__all__ = [
    "Error",
    "UsageError",
    "InputError",
    "ResourceError",
    "MismatchError",
    "Warning",
]
