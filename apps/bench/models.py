"""Benchmark results in the database, mirroring the results/ tree (which stays authoritative)."""

from __future__ import annotations

from django.db import models


class BenchmarkRun(models.Model):
    name = models.CharField(max_length=200, unique=True)
    config = models.JSONField(default=dict, blank=True)
    agent = models.CharField(
        max_length=200,
        blank=True,
        help_text="built-in agent used, if any (control agent, or reference agent on its model)",
    )
    speed_factor = models.FloatField(default=1.0)
    results_dir = models.CharField(max_length=500, blank=True)
    started_at = models.DateTimeField(null=True, blank=True)
    finished_at = models.DateTimeField(null=True, blank=True)

    class Meta:
        ordering = ["-started_at", "name"]

    def __str__(self) -> str:
        return self.name


class TaskResult(models.Model):
    benchmark = models.ForeignKey(BenchmarkRun, on_delete=models.CASCADE, related_name="tasks")
    scenario_id = models.CharField(max_length=200)
    trial = models.PositiveIntegerField(default=1, help_text="bench run --trials: which run")
    environment = models.CharField(max_length=64)
    category = models.CharField(max_length=64, blank=True)
    success = models.BooleanField(
        null=True, help_text="null when the outcome is an error, ours or the setup's (see error)"
    )
    reaction_time = models.FloatField(null=True, blank=True, help_text="wall seconds")
    condition_at = models.FloatField(null=True, blank=True, help_text="wall seconds")
    evaluation_time = models.FloatField(null=True, blank=True, help_text="wall seconds")
    input_tokens = models.BigIntegerField(null=True, blank=True)
    output_tokens = models.BigIntegerField(null=True, blank=True)
    tool_calls = models.IntegerField(null=True, blank=True)
    cost_usd = models.FloatField(null=True, blank=True)
    costs = models.JSONField(null=True, blank=True, help_text="the agent's costs.json")
    result = models.JSONField(null=True, blank=True, help_text="results.json")
    run = models.ForeignKey(
        "events.Run", null=True, blank=True, on_delete=models.SET_NULL, related_name="+"
    )
    error = models.TextField(blank=True)
    recorded_at = models.DateTimeField(auto_now=True)

    class Meta:
        ordering = ["benchmark", "environment", "scenario_id", "trial"]
        constraints = [
            models.UniqueConstraint(
                fields=["benchmark", "scenario_id", "trial"], name="bench_one_result_per_trial"
            ),
        ]

    def __str__(self) -> str:
        trial = f" (trial {self.trial})" if self.trial != 1 else ""
        return f"{self.benchmark}: {self.scenario_id}{trial}"
