"""What a run's log said when it was recorded, so a later refold can be checked against it."""

from __future__ import annotations

from django.db import models

from events.models import Run

# What a verdict says, recorded or refolded: a replay compares exactly these.
VERDICT_FIELDS = ("success", "detail", "graded_at_seq", "event_count", "state_digest", "log_digest")


class RunVerdict(models.Model):
    """A verdict and state digest recorded for a run (on export, on import, from the admin).

    `replay` refolds the log from scratch and compares with the latest record: a different
    verdict, state digest or log digest means the log or the code changed since.
    """

    run = models.ForeignKey(Run, on_delete=models.CASCADE, related_name="verdicts")
    success = models.BooleanField()
    detail = models.TextField(blank=True)
    graded_at_seq = models.PositiveIntegerField(null=True, blank=True)
    event_count = models.PositiveIntegerField()
    state_digest = models.CharField(max_length=64, help_text="sha256 of the materialised tables")
    log_digest = models.CharField(max_length=64, help_text="sha256 of the logged events")
    source = models.CharField(max_length=32, default="recorded")
    recorded_at = models.DateTimeField(auto_now_add=True)

    class Meta:
        ordering = ["-id"]
        get_latest_by = "id"

    def __str__(self) -> str:
        return f"run {self.run_id}: {'pass' if self.success else 'fail'} ({self.source})"

    def as_dict(self) -> dict:
        return {name: getattr(self, name) for name in VERDICT_FIELDS}
