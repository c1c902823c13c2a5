"""/media/…: generated images (mounted by sentinel_site/urls.py)."""

from django.urls import path

from apps.media import views

app_name = "media"

urlpatterns = [
    path("avatars/<str:slug>.svg", views.drawn, {"kind": "avatars"}, name="avatar"),
    path("logos/<str:slug>.svg", views.drawn, {"kind": "logos"}, name="logo"),
    path("banners/<str:slug>.svg", views.drawn, {"kind": "banners"}, name="banner"),
    path("pictures/<str:subject>/<str:slug>.svg", views.picture, name="picture"),
    path("posters/<str:subject>/<str:slug>.svg", views.poster, name="poster"),
    path(
        "tall-posters/<str:subject>/<str:slug>.svg",
        views.poster,
        {"tall": True},
        name="tall-poster",
    ),
    path(
        "thumbnails/<str:subject>/<str:seed>/<str:caption>.svg",
        views.thumbnail,
        {"shape": "wide"},
        name="thumbnail",
    ),
    path(
        "tall-thumbnails/<str:subject>/<str:seed>/<str:caption>.svg",
        views.thumbnail,
        {"shape": "tall"},
        name="tall-thumbnail",
    ),
    path("covers/<str:slug>.svg", views.drawn, {"kind": "covers"}, name="cover"),
    path("audio/<str:slug>.wav", views.audio, name="audio"),
    # Anything else under /media/ names a kind we do not draw: a 404 that says so.
    path("<str:kind>/<str:slug>.svg", views.drawn, name="unknown-kind"),
]
