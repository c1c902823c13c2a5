"""MicroFy pages: thin views over `page.state`, actions through `page.act`.

Every screen has its own URL (urls.py). Actions are POST forms carrying a `back` path (relative
to the environment root) and returning there (post/redirect/get, `apps.kit.rendering`). What a page shows that moves
with the clock — the player's position, an artist's listeners, a track's plays — registers when
it next changes (`page.changes_at`), so kept screens and live pushes never show a stale value.
"""

from __future__ import annotations

from django.http import Http404, HttpRequest, HttpResponse

from apps.kit.item_actions import act_on_item
from apps.kit.pages import Page, form_view, screen_view
from apps.kit.rendering import back_field, redirect_after, render_screen
from apps.kit.streaming import COUNT_REFRESH_S, present, showing, shown_count
from apps.microfy import screens
from apps.microfy.query import HomeQuery, SearchQuery
from apps.microfy.state import LIKED, Music, Track

TRACK_ACTIONS = {
    "play_track": "",
    "like_track": "Added to Liked Songs",
    "unlike_track": "Removed from Liked Songs",
    "add_to_playlist": "Added to playlist",
}
TRACK_FORMS = {"add_to_playlist": ("playlist_id",)}  # what a track action's form posts
ARTIST_ACTIONS = {"follow_artist": "Following", "unfollow_artist": "Unfollowed"}


def plays(page: Page, track: Track) -> int:
    """A track's plays as shown now; an open page takes a new number up at its next refresh."""
    showing(page, track.plays, refresh=COUNT_REFRESH_S)
    return screens.plays_at(page.state, track, page.now)


def base_context(page: Page, section: str, here: str, q: str = "") -> dict:
    music: Music = page.state
    player, changes = screens.player(music, page.now)
    page.changes_at(changes)
    return {
        "section": section,
        "here": here,
        "search_q": q,
        "self_name": music.self_name,
        "library": screens.library_entries(music),
        "player": player,
        "player_liked": bool(player and music.is_liked(player.track.id)),
        "followed_count": len(music.followed),
    }


def cards(music: Music, tracks: tuple[Track, ...]) -> list[tuple[Track, bool]]:
    return [(t, music.is_liked(t.id)) for t in tracks]


@screen_view
def home(request: HttpRequest, page: Page) -> HttpResponse:
    query = HomeQuery.from_params(request.GET)
    music: Music = page.state
    if query.mood is not None and query.mood not in music.moods:
        raise Http404("no such mood")
    context = {
        **base_context(page, "home", query.querystring()),
        "trending": screens.trending(music),
        "new_releases": screens.new_releases(music),
        "artists": screens.top_artists(music)[: screens.HOME_ARTISTS],
        "moods": tuple(music.moods.values()),
        "mood": query.mood,
        "playlists": tuple(music.playlists.values()),
    }
    return render_screen(request, page, "microfy/home.html", context)


@screen_view
def search(request: HttpRequest, page: Page) -> HttpResponse:
    query = SearchQuery.from_params(request.GET)
    results = screens.search(page.state, query.q)
    context = {
        **base_context(page, "search", "search" + query.querystring(), query.q),
        "results": results,
        "song_rows": cards(page.state, results.tracks),
        "q": query.q,
        "genres": tuple(dict.fromkeys(t.genre for t in screens.trending(page.state)))[:12],
    }
    return render_screen(request, page, "microfy/search.html", context)


@screen_view
def track(request: HttpRequest, page: Page, track_id: str) -> HttpResponse:
    music: Music = page.state
    song = present(music.tracks.get(track_id), "track")
    artist = screens.visible_artist(music, song.artist_id)
    context = {
        **base_context(page, "track", f"track/{track_id}"),
        "track": song,
        "liked": music.is_liked(track_id),
        "plays": plays(page, song),
        "artist": artist,
        "more_by_artist": [
            t for t in screens.artist_tracks(music, song.artist_id) if t.id != track_id
        ],
        "user_playlists": music.own_playlists(),
        "lyrics": [block.split("\n") for block in song.lyrics.split("\n\n") if block.strip()],
    }
    return render_screen(request, page, "microfy/track.html", context)


@screen_view
def artist(request: HttpRequest, page: Page, artist_id: str) -> HttpResponse:
    music: Music = page.state
    found = present(screens.visible_artist(music, artist_id), "artist")
    tracks = screens.artist_tracks(music, artist_id)
    # Its followers and listeners move too: an open page takes them up at its next refresh.
    showing(page, found.followers, refresh=COUNT_REFRESH_S)
    popular = sorted(tracks, key=lambda t: t.plays.value_at(0), reverse=True)[: screens.POPULAR]
    context = {
        **base_context(page, "artist", f"artist/{artist_id}"),
        "artist": found,
        "following": music.is_followed(artist_id),
        "listeners": shown_count(showing(page, found.listeners, refresh=COUNT_REFRESH_S)),
        "followers": screens.follower_count(music, found, page.now),
        "popular": [(t, music.is_liked(t.id), plays(page, t)) for t in popular],
        "discography": tuple(dict.fromkeys(t.album for t in tracks)),
        "fans_also_like": [
            a for a in screens.top_artists(music) if a.genre == found.genre and a.id != artist_id
        ][:6],
    }
    return render_screen(request, page, "microfy/artist.html", context)


@screen_view
def playlist(request: HttpRequest, page: Page, playlist_id: str) -> HttpResponse:
    music: Music = page.state
    tracks = screens.playlist_tracks(music, playlist_id)
    found = None if playlist_id == LIKED else present(music.playlist(playlist_id), "playlist")
    context = {
        **base_context(page, "playlist", f"playlist/{playlist_id}"),
        "playlist": found,
        "playlist_id": playlist_id,
        "owner_name": found.owner_name if found else music.self_name,
        "rows": cards(music, tracks),
        "total_s": sum(t.duration_s for t in tracks),
    }
    return render_screen(request, page, "microfy/playlist.html", context)


@form_view
def track_action(request: HttpRequest, page: Page, track_id: str, action: str) -> HttpResponse:
    done = act_on_item(request, page, action, TRACK_ACTIONS, "track_id", track_id, TRACK_FORMS)
    return redirect_after(request, page, back_field(request), done)


@form_view
def artist_action(request: HttpRequest, page: Page, artist_id: str, action: str) -> HttpResponse:
    done = act_on_item(request, page, action, ARTIST_ACTIONS, "artist_id", artist_id)
    return redirect_after(request, page, back_field(request), done)


@form_view
def create_playlist(request: HttpRequest, page: Page) -> HttpResponse:
    form = {field: request.POST.get(field, "") for field in ("name", "description")}
    created = page.act("create_playlist", form).payload
    path = f"playlist/{created['playlist_id']}"
    return redirect_after(request, page, path, f"Created {created['name']}")
