"""Tally pages, mounted by the core under /r/<token>/tally/ (`token` is a URL kwarg).

GET  ./        the tally: total, level, entries, and the Poke form
POST ./poke    poke (field `n`), then back to the tally
"""

from django.urls import path

from apps.tally import views

urlpatterns = [
    path("", views.tally, name="tally"),
    path("poke", views.poke, name="poke"),
]
