"""The certificate register keyed by the laboratory's code, never its display name; who prepared
and who authorised each certificate; what an amendment changed; the "as found" test of an
"as found / as left" certificate (ISO/IEC 17025:2017 §7.8.2.1 d and o, §7.8.4.1 d, §7.8.8.3).

Before this revision ``certificate.laboratory`` held the laboratory's *name*: a full stop added
to the name started a second counter and gave a number a second time. The code is the part of
``series`` before ``|`` (every series was formed as ``CODE|YEAR``, ``CODE`` or ``CODE|fixed``);
the name moves to ``laboratory_name``. Where two rows of one code already share a number (the
fault this revision ends), the later keeps its old key (the name) so that no row is lost and the
two stay told apart; ``certificate list`` shows both.

Revision ID: 0005
Revises: 0004
"""
import sqlalchemy as sa
from alembic import op

revision = "0005"
down_revision = "0004"
branch_labels = None
depends_on = None

_COLUMNS = (("laboratory_name", sa.String(200)), ("prepared_by", sa.String(200)),
            ("approved_by", sa.String(200)), ("approved_role", sa.String(200)))


def upgrade() -> None:
    with op.batch_alter_table("certificate") as batch:
        for name, type_ in _COLUMNS:
            batch.add_column(sa.Column(name, type_, nullable=False, server_default=""))
        batch.add_column(sa.Column("changes_json", sa.Text, nullable=False,
                                   server_default="[]"))
        batch.add_column(sa.Column("as_found_test_id", sa.Integer, nullable=True))
    cert = sa.table("certificate", sa.column("id", sa.Integer),
                    sa.column("laboratory", sa.String), sa.column("laboratory_name", sa.String),
                    sa.column("series", sa.String), sa.column("number", sa.String))
    conn = op.get_bind()
    rows = conn.execute(sa.select(cert.c.id, cert.c.laboratory, cert.c.series, cert.c.number)
                        .order_by(cert.c.id)).all()
    taken = set()
    for id_, name, series, number in rows:
        code = series.split("|", 1)[0] or name
        key = code if (code, number) not in taken else name
        taken.add((key, number))
        conn.execute(sa.update(cert).where(cert.c.id == id_)
                     .values(laboratory=key, laboratory_name=name))


def downgrade() -> None:
    cert = sa.table("certificate", sa.column("laboratory", sa.String),
                    sa.column("laboratory_name", sa.String))
    op.get_bind().execute(sa.update(cert).values(laboratory=cert.c.laboratory_name))
    with op.batch_alter_table("certificate") as batch:
        for name in ("as_found_test_id", "changes_json", *(n for n, _ in _COLUMNS)):
            batch.drop_column(name)
