"""MicroTube pages, mounted by the core under /r/<token>/microtube/ (`token` is a URL kwarg).

GET  ./                           Home: every video
GET  ./feed/subscriptions         videos of subscribed channels
GET  ./shorts  ./shorts/<id>      the Shorts shelf and player (like, dislike, subscribe, comment)
GET  ./feed/history  ./feed/you  ./feed/playlists   ./playlist?list=<id> (WL, LL, pl-user-n)
GET  ./watch?v=<id>               the player (opening it is watching: history)
POST ./videos/<id>/<action>       like_video, unlike_video, dislike_video, undislike_video,
                                  save_video, unsave_video, post_comment (field `content`),
                                  add_to_playlist (field `playlist_id`); `back=shorts`
                                  returns to the Shorts player
POST ./playlists/new              fields `name`, optional `video_id`
GET  ./channel/<id>?tab=          videos | playlists | about
POST ./channel/<id>/<action>      subscribe | unsubscribe (optional `video_id`: back to it)
GET  ./results?search_query=<q>
GET  ./notifications
POST ./notifications/<action>     read_notification (then to its video) | dismiss_notification
"""

from django.urls import path

from apps.microtube import views

urlpatterns = [
    path("", views.home, name="home"),
    path("feed/subscriptions", views.subscriptions, name="subscriptions"),
    path("shorts", views.shorts, name="shorts"),
    path("shorts/<str:video_id>", views.short, name="short"),
    path("feed/history", views.history, name="history"),
    path("feed/you", views.you, name="you"),
    path("feed/playlists", views.playlists, name="playlists"),
    path("playlist", views.playlist, name="playlist"),
    path("playlists/new", views.new_playlist, name="new-playlist"),
    path("watch", views.watch, name="watch"),
    path("videos/<str:video_id>/<str:action>", views.video_action, name="video-action"),
    path("channel/<str:channel_id>", views.channel, name="channel"),
    path("channel/<str:channel_id>/<str:action>", views.channel_action, name="channel-action"),
    path("results", views.results, name="results"),
    path("notifications", views.notifications, name="notifications"),
    path("notifications/<str:action>", views.notification_action, name="notification-action"),
]
