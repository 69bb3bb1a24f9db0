"""A sign-off saved for approval (issue 40): the form a preparer filled for a test, kept until
an authorised signatory (another account) approves and issues it, so the certificate's preparer
is an account of the history, not a name typed on the form (ISO/IEC 17025:2017 §7.8.2.1 o,
§6.2.6). One row a test (the newest save); every save is also an audit entry.

Revision ID: 0007
Revises: 0006
"""
import sqlalchemy as sa
from alembic import op

revision = "0007"
down_revision = "0006"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "signoff_for_approval",
        sa.Column("test_id", sa.Integer, sa.ForeignKey("test.id", ondelete="CASCADE"),
                  primary_key=True),
        sa.Column("values_json", sa.Text, nullable=False),
        sa.Column("by", sa.String(200), nullable=False),
        sa.Column("saved", sa.DateTime, nullable=False))


def downgrade() -> None:
    op.drop_table("signoff_for_approval")
