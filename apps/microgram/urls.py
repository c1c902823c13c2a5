"""MicroGram pages, mounted by the core under /r/<token>/microgram/ (`token` is a URL kwarg).

GET  ./?page=                         home: story bar and feed (10 posts a page, newest first)
GET  ./p/<post>/                      one post with its comments (opening it views it)
POST ./p/<post>/<action>              like_post, unlike_post, save_post, unsave_post,
                                      comment_post (field `text`)
POST ./p/<post>/share                 fields `conversation_id`, `text`: send it in a DM
GET  ./stories/<story>/               the story viewer (opening it watches the story)
GET  ./explore/?q=   ./search/?q=     the Explore grid; people search
GET  ./direct/inbox/                  DM threads
GET  ./direct/t/<thread>/             one thread (opening it reads it)
POST ./direct/t/<thread>/send         field `text`
GET  ./activity/                      notifications
POST ./activity/read                  field `activity_id`, then to what it is about
POST ./activity/read-all
GET  ./profile/<user>/?tab=           posts | saved | tagged
GET  ./profile/<user>/following/      the self user's following list
POST ./profile/<user>/message         the DM thread with them (new if none; followed only)
POST ./profile/<user>/<verb>          follow | unfollow
"""

from django.urls import path

from apps.microgram import views

urlpatterns = [
    path("", views.feed, name="feed"),
    path("p/<str:post_id>/", views.post, name="post"),
    path("p/<str:post_id>/share", views.share, name="share"),
    path("p/<str:post_id>/<str:action>", views.post_action, name="post-action"),
    path("stories/<str:story_id>/", views.story, name="story"),
    path("explore/", views.explore, name="explore"),
    path("search/", views.search, name="search"),
    path("direct/inbox/", views.inbox, name="inbox"),
    path("direct/t/<str:conversation_id>/", views.thread, name="thread"),
    path("direct/t/<str:conversation_id>/send", views.send_message, name="send"),
    path("activity/", views.activity, name="activity"),
    path("activity/read", views.read_activity, name="read-activity"),
    path("activity/read-all", views.read_all_activity, name="read-all-activity"),
    path("profile/<str:user_id>/", views.profile, name="profile"),
    path("profile/<str:user_id>/following/", views.following, name="following"),
    path("profile/<str:user_id>/message", views.message, name="message"),
    path("profile/<str:user_id>/<str:verb>", views.follow, name="follow"),
]
