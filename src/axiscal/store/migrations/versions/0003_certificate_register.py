"""The certificate register: numbers unique per laboratory, the issued document and its SHA-256,
amendments (ISO/IEC 17025:2017 §7.8.2.1 b, §7.8.8).

Revision ID: 0003
Revises: 0002
"""
import sqlalchemy as sa
from alembic import op

revision = "0003"
down_revision = "0002"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "certificate",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("test_id", sa.Integer, sa.ForeignKey("test.id", ondelete="CASCADE"),
                  nullable=False),
        sa.Column("laboratory", sa.String(200), nullable=False),
        sa.Column("series", sa.String(250), nullable=False),
        sa.Column("counter", sa.Integer, nullable=False),
        sa.Column("number", sa.String(100), nullable=False),
        sa.Column("customer", sa.String(400), nullable=False),
        sa.Column("issued", sa.String(40), nullable=False),
        sa.Column("status", sa.String(20), nullable=False),
        sa.Column("replaces_id", sa.Integer, sa.ForeignKey("certificate.id"), nullable=True),
        sa.Column("reason", sa.Text, nullable=False),
        sa.Column("media_type", sa.String(40), nullable=False),
        sa.Column("document", sa.LargeBinary, nullable=False),
        sa.Column("sha256", sa.String(64), nullable=False),
        sa.Column("inputs_json", sa.Text, nullable=False),
        sa.Column("created", sa.DateTime, nullable=False),
        sa.UniqueConstraint("laboratory", "number", name="uq_certificate_number"),
        sa.UniqueConstraint("laboratory", "series", "counter", name="uq_certificate_counter"))


def downgrade() -> None:
    op.drop_table("certificate")
