"""Compensation tables written from a test (added after the first schema: the upgrade path of
a database made by an earlier version is tested).

Revision ID: 0002
Revises: 0001
"""
import sqlalchemy as sa
from alembic import op

revision = "0002"
down_revision = "0001"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "compensation_table",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("test_id", sa.Integer, sa.ForeignKey("test.id", ondelete="CASCADE"),
                  nullable=False),
        sa.Column("controller", sa.String(40), nullable=False),
        sa.Column("filename", sa.String(300), nullable=False),
        sa.Column("text", sa.Text, nullable=False),
        sa.Column("created", sa.DateTime, nullable=False))


def downgrade() -> None:
    op.drop_table("compensation_table")
