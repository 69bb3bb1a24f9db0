"""The laboratory kept in the history, and drift checks kept beside their tests (issue 40).

``laboratory`` holds one row: the tables of a configuration that identify the laboratory and
what it certifies with (``[company]`` name, address and code, ``[[signatory]]``,
``[[instrument]]``, ``[uncertainty]`` with E_VE declared and the CMC), so a certificate can be
issued from the workbench without editing a file on the server; every change is an audit entry
(ISO/IEC 17025:2017 §7.5.2). ``drift_check`` keeps each drift-check file uploaded for a test, byte
for byte with its SHA-256, and the E_VE it gives (ISO 230-2:2014 Annex A.5).

Revision ID: 0006
Revises: 0005
"""
import sqlalchemy as sa
from alembic import op

revision = "0006"
down_revision = "0005"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "laboratory",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("tables_json", sa.Text, nullable=False),
        sa.Column("updated", sa.DateTime, nullable=False),
        sa.Column("updated_by", sa.String(200), nullable=False))
    op.create_table(
        "drift_check",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("test_id", sa.Integer, sa.ForeignKey("test.id", ondelete="CASCADE"),
                  nullable=False),
        sa.Column("filename", sa.String(300), nullable=False),
        sa.Column("raw", sa.LargeBinary, nullable=False),
        sa.Column("sha256", sa.String(64), nullable=False),
        sa.Column("e_ve", sa.Float(53), nullable=False),
        sa.Column("readings", sa.Integer, nullable=False),
        sa.Column("created", sa.DateTime, nullable=False),
        sa.Column("by", sa.String(200), nullable=False))
    op.create_index("ix_drift_check_test", "drift_check", ["test_id"])


def downgrade() -> None:
    op.drop_index("ix_drift_check_test", "drift_check")
    op.drop_table("drift_check")
    op.drop_table("laboratory")
