"""MicroChat pages, mounted by the core under /r/<token>/microchat/ (`token` is a URL kwarg).

GET  ./?filter=&find=&reply=&conversation=   chats (opening a conversation marks it read)
GET  ./search?q=                             global search: chats and messages
GET  ./teams, ./teams/<team>[/<channel>]     teams and their channels
GET  ./calendar?view=&offset=                the calendar (day, work week, month)
GET  ./calls?filter=                         recent and missed calls
GET  ./activity                              missed calls and reactions to your messages
POST ./send                                  send_message (conversation_id, content, reply_to)
POST ./conversations/<action>                pin, unpin, mute, unmute, mark_unread
POST ./messages/<action>                     react, unreact, edit_message, delete_message
"""

from django.urls import path

from apps.microchat import views

urlpatterns = [
    path("", views.chat, name="chat"),
    path("search", views.search, name="search"),
    path("teams", views.teams, name="teams"),
    path("teams/<str:team_id>", views.team, name="team"),
    path("teams/<str:team_id>/<str:channel_id>", views.team, name="channel"),
    path("calendar", views.calendar, name="calendar"),
    path("calls", views.calls, name="calls"),
    path("activity", views.activity, name="activity"),
    path("send", views.send, name="send"),
    path("conversations/<str:action>", views.conversation_action, name="conversation-action"),
    path("messages/<str:action>", views.message_action, name="message-action"),
]
