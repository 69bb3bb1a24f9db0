"""Who may use the workbench, and the protections every request passes through.

* **Localhost alone needs no login.** Served on a loopback address (the default, 127.0.0.1) the
  workbench is a single user's desktop tool and everyone who can reach it is an engineer.
* **Any other address needs accounts.** ``axiscal serve --host 0.0.0.0`` refuses to start unless a
  users file names at least one account (``axiscal serve --add-user NAME --role engineer``).
  Passwords are stored as Argon2id hashes (argon2-cffi, the reference implementation's binding;
  OWASP Password Storage Cheat Sheet recommends Argon2id). A login gives a session kept by the
  server (:mod:`axiscal.web.sessions`: ended at log-out, after 30 min idle or 12 h), its random
  identifier in an HttpOnly, SameSite=Strict cookie; wrong passwords are backed off per account
  and per address.
* **Roles.** ``viewer`` reads every page and download; ``engineer`` also uploads, stores and writes
  compensation tables.
* **CSRF.** Every form and every htmx request carries a token bound to the session (the
  synchronizer-token pattern of the OWASP CSRF Prevention Cheat Sheet); a POST without it is
  refused.
* **Uploads** are limited in size, their declared content type must be a text or octet-stream
  type, and their name must end in a format axiscal reads; a name is never used as a path.
"""

from __future__ import annotations

import ipaddress
import secrets
from dataclasses import dataclass, field
from pathlib import Path

from axiscal.errors import ConfigError, InputError

__all__ = ["ROLES", "User", "UserFile", "is_loopback", "MAX_UPLOAD_BYTES",
           "UPLOAD_TYPES", "UPLOAD_SUFFIXES", "check_upload"]

ROLES = ("viewer", "engineer")
#: Largest upload accepted, bytes (a positioning file is kilobytes; a long capture megabytes).
MAX_UPLOAD_BYTES = 20 * 1024 * 1024
#: Content types a browser sends for the files axiscal reads.
UPLOAD_TYPES = ("text/csv", "text/plain", "application/json", "application/octet-stream",
                "application/vnd.ms-excel", "text/x-csv", "application/csv", "application/toml",
                "")
#: File name endings of the data files the workbench evaluates.
UPLOAD_SUFFIXES = (".csv", ".json", ".txt", ".dat", ".ecmc", ".rtl", ".rta", ".toml")


@dataclass(frozen=True)
class User:
    """One account: a name, its role and the Argon2id hash of its password."""

    name: str
    role: str
    password_hash: str


@dataclass
class UserFile:
    """The accounts of a workbench, kept in a small TOML file (``[users.NAME]``)."""

    path: Path
    users: dict = field(default_factory=dict)

    @classmethod
    def load(cls, path) -> "UserFile":
        """Read the users file (an absent file has no accounts)."""
        p = Path(path)
        if p.is_symlink() and not p.exists():
            raise ConfigError(f"{p}: a symbolic link to nothing (or a loop of links)")
        if not p.exists():
            return cls(p)
        from axiscal._schema import loads_toml
        from axiscal.io._files import read_text

        data = loads_toml(read_text(p), str(p))
        users = {}
        for name, u in (data.get("users") or {}).items():
            if not isinstance(u, dict) or u.get("role") not in ROLES or \
                    not str(u.get("password_hash", "")).startswith("$argon2"):
                raise ConfigError(f"{p}: [users.{name}] needs role (viewer or engineer) and an "
                                  "argon2 password_hash")
            users[name] = User(name, u["role"], u["password_hash"])
        return cls(p, users)

    def add(self, name: str, role: str, password: str) -> User:
        """Add or replace an account and write the file (mode 0600: it holds hashes)."""
        import os

        from argon2 import PasswordHasher

        if not name or not name.replace("-", "").replace("_", "").replace(".", "").isalnum():
            raise InputError(f"user name {name!r}: letters, digits, '-', '_' and '.' only")
        if role not in ROLES:
            raise InputError(f"role {role!r}: viewer or engineer")
        if len(password) < 8:
            raise InputError("a password needs at least 8 characters")
        user = User(name, role, PasswordHasher().hash(password))
        self.users[name] = user
        lines = ["# axiscal workbench accounts (Argon2id hashes)"]
        for u in self.users.values():
            lines += [f'[users."{u.name}"]', f'role = "{u.role}"',
                      f'password_hash = "{u.password_hash}"', ""]
        self.path.parent.mkdir(parents=True, exist_ok=True)
        tmp = self.path.with_name(f".{self.path.name}.tmp")
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write("\n".join(lines))
        os.replace(tmp, self.path)
        return user

    def check(self, name: str, password: str) -> User | None:
        """The user if the password is right, else None (constant work for unknown names)."""
        from argon2 import PasswordHasher
        from argon2.exceptions import VerificationError, InvalidHashError

        ph = PasswordHasher()
        user = self.users.get(name)
        target = user.password_hash if user else _dummy_hash()
        try:
            ph.verify(target, password)
        except (VerificationError, InvalidHashError):
            return None
        return user


_DUMMY: list[str] = []


def _dummy_hash() -> str:
    """Hash of a random password, verified against for unknown names so timing tells nothing."""
    if not _DUMMY:
        from argon2 import PasswordHasher

        _DUMMY.append(PasswordHasher().hash(secrets.token_hex(16)))
    return _DUMMY[0]


def is_loopback(host: str) -> bool:
    """True for 127.0.0.0/8, ::1 and ``localhost``."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def check_upload(filename: str, content_type: str, size: int,
                 limit: int = MAX_UPLOAD_BYTES, suffixes: tuple = UPLOAD_SUFFIXES,
                 types: tuple = UPLOAD_TYPES) -> str:
    """The upload's suffix if acceptable (one of ``suffixes``, sent as one of ``types``); else
    an :class:`InputError` naming the problem."""
    name = Path(filename or "").name
    suffix = Path(name).suffix.lower()
    if not name or suffix not in suffixes:
        raise InputError(f"file {name or '(none)'!r}: upload a data file ending in "
                         f"{', '.join(suffixes)}")
    base = (content_type or "").split(";")[0].strip().lower()
    if base not in types:
        raise InputError(f"file {name!r} was sent as {base!r}; a data file is text "
                         "(CSV, JSON) or an instrument's binary record")
    if size > limit:
        from axiscal.web.guards import TooLarge       # HTTP 413, as a body over the limit

        raise TooLarge(f"file {name!r} is larger than the workbench takes: at most "
                       f"{limit / 2**20:.3g} MiB")
    if size == 0:
        raise InputError(f"file {name!r} is empty")
    return suffix
