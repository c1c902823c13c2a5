"""MicroFy pages, mounted by the core under /r/<token>/microfy/ (`token` is a URL kwarg).

GET  ./?mood=                      home: trending, new releases, artists, moods, your playlists
GET  ./search?q=                   search tracks, artists and playlists
GET  ./track/<id>                  a song: play, like, add to playlist, lyrics
GET  ./artist/<id>                 an artist: follow, popular tracks, listeners, followers
GET  ./playlist/<id>               a playlist (`liked` = Liked Songs)
POST ./tracks/<id>/<action>        play_track, like_track, unlike_track, add_to_playlist
POST ./artists/<id>/<action>       follow_artist, unfollow_artist
POST ./playlists                   create_playlist (name, description)
"""

from django.urls import path

from apps.microfy import views

urlpatterns = [
    path("", views.home, name="home"),
    path("search", views.search, name="search"),
    path("track/<str:track_id>", views.track, name="track"),
    path("artist/<str:artist_id>", views.artist, name="artist"),
    path("playlist/<str:playlist_id>", views.playlist, name="playlist"),
    path("tracks/<str:track_id>/<str:action>", views.track_action, name="track-action"),
    path("artists/<str:artist_id>/<str:action>", views.artist_action, name="artist-action"),
    path("playlists", views.create_playlist, name="create-playlist"),
]
