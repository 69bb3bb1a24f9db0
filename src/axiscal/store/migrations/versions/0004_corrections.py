"""Corrections that lose nothing: the audit trail of every change (who, when, what, why, old
and new values) and the withdrawal of a test with its reason (ISO/IEC 17025:2017 §7.5.2 and
§8.4.2: changes to records are traceable to the previous version, the original kept).

Revision ID: 0004
Revises: 0003
"""
import sqlalchemy as sa
from alembic import op

revision = "0004"
down_revision = "0003"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "audit",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("at", sa.DateTime, nullable=False),
        sa.Column("by", sa.String(200), nullable=False),
        sa.Column("action", sa.String(40), nullable=False),
        sa.Column("what", sa.Text, nullable=False),
        sa.Column("reason", sa.Text, nullable=False),
        sa.Column("machine_id", sa.Integer, nullable=True),
        sa.Column("axis_id", sa.Integer, nullable=True),
        sa.Column("test_id", sa.Integer, nullable=True),
        sa.Column("old_json", sa.Text, nullable=False),
        sa.Column("new_json", sa.Text, nullable=False))
    op.create_index("ix_audit_machine", "audit", ["machine_id"])
    op.create_index("ix_audit_test", "audit", ["test_id"])
    with op.batch_alter_table("test") as batch:
        batch.add_column(sa.Column("withdrawn", sa.Text, nullable=False, server_default=""))


def downgrade() -> None:
    with op.batch_alter_table("test") as batch:
        batch.drop_column("withdrawn")
    op.drop_index("ix_audit_test", "audit")
    op.drop_index("ix_audit_machine", "audit")
    op.drop_table("audit")
