"""The first history schema: machines, axes, tests with their raw files and evaluations.

Revision ID: 0001
Revises:
"""
import sqlalchemy as sa
from alembic import op

revision = "0001"
down_revision = None
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "machine",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("name", sa.String(200), nullable=False, unique=True),
        sa.Column("maker", sa.String(200), nullable=False),
        sa.Column("model", sa.String(200), nullable=False),
        sa.Column("serial", sa.String(200), nullable=False),
        sa.Column("location", sa.String(200), nullable=False),
        sa.Column("created", sa.DateTime, nullable=False))
    op.create_table(
        "axis",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("machine_id", sa.Integer, sa.ForeignKey("machine.id", ondelete="CASCADE"),
                  nullable=False),
        sa.Column("name", sa.String(50), nullable=False),
        sa.Column("kind", sa.String(20), nullable=False),
        sa.UniqueConstraint("machine_id", "name"))
    op.create_table(
        "test",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("axis_id", sa.Integer, sa.ForeignKey("axis.id", ondelete="CASCADE"),
                  nullable=False),
        sa.Column("kind", sa.String(40), nullable=False),
        sa.Column("tested_at", sa.DateTime, nullable=False),
        sa.Column("date_known", sa.Boolean, nullable=False),
        sa.Column("stored_at", sa.DateTime, nullable=False),
        sa.Column("instrument", sa.String(200), nullable=False),
        sa.Column("operator", sa.String(200), nullable=False),
        sa.Column("note", sa.Text, nullable=False),
        sa.Column("filename", sa.String(300), nullable=False),
        sa.Column("sha256", sa.String(64), nullable=False, unique=True),
        sa.Column("raw", sa.LargeBinary, nullable=False),
        sa.Column("dataset_json", sa.Text, nullable=False),
        sa.Column("result_json", sa.Text, nullable=False),
        sa.Column("environment_json", sa.Text, nullable=False),
        sa.Column("axiscal_version", sa.String(40), nullable=False))
    op.create_index("ix_test_axis_date", "test", ["axis_id", "tested_at"])
    op.create_table(
        "parameter",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("test_id", sa.Integer, sa.ForeignKey("test.id", ondelete="CASCADE"),
                  nullable=False),
        sa.Column("name", sa.String(60), nullable=False),
        sa.Column("value", sa.Double, nullable=False),
        sa.Column("unit", sa.String(20), nullable=False),
        sa.UniqueConstraint("test_id", "name"))
    op.create_index("ix_parameter_name", "parameter", ["name"])


def downgrade() -> None:
    op.drop_table("parameter")
    op.drop_table("test")
    op.drop_table("axis")
    op.drop_table("machine")
