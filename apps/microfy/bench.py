"""The MicroFy pages worth timing (`manage.py bench_pages --env microfy`), from the state.

A pure function of the library: home, a search, a track, an artist, a catalog playlist, Liked
Songs and a mood. Paths are relative to the environment root (`/r/<token>/microfy/`).
"""

from __future__ import annotations

from apps.microfy import screens
from apps.microfy.state import LIKED, Music


def sample_pages(music: Music) -> list[str]:
    pages = ["", "search?q=the", f"playlist/{LIKED}"]
    trending = screens.trending(music)
    if trending:
        track = trending[0]
        pages += [f"track/{track.id}", f"artist/{track.artist_id}"]
        pages.append("search?q=" + track.title.split()[0].lower())
    pages += [f"playlist/{playlist_id}" for playlist_id in list(music.playlists)[:2]]
    pages += [f"?mood={mood_id}" for mood_id in list(music.moods)[:1]]
    return pages
