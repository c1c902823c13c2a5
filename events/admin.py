"""Runs and their logs in the admin. Events are read-only: the log is append-only."""

from django.contrib import admin

from events.models import Event, Run


class EventInline(admin.TabularInline):
    model = Event
    fields = ("seq", "at", "kind", "type", "payload", "timeline_index", "lateness_ms")
    readonly_fields = fields
    extra = 0
    can_delete = False
    show_change_link = False

    def has_add_permission(self, request, obj=None):
        return False


@admin.register(Run)
class RunAdmin(admin.ModelAdmin):
    list_display = ("id", "scenario_id", "environment", "status", "clock_mode", "speed_factor", "created_at",
                    "closed_at")
    list_filter = ("status", "environment", "clock_mode")
    search_fields = ("scenario_id", "token")
    readonly_fields = ("token", "catalog_dir", "catalog_hash", "created_at")
    inlines = [EventInline]


@admin.register(Event)
class EventAdmin(admin.ModelAdmin):
    list_display = ("run", "seq", "at", "kind", "type", "lateness_ms")
    list_filter = ("kind",)

    def has_add_permission(self, request):
        return False

    def has_change_permission(self, request, obj=None):
        return False

    def has_delete_permission(self, request, obj=None):
        return False
