"""MicroDin pages, mounted by the core under /r/<token>/microdin/ (`token` is a URL kwarg).

GET  ./                                  home feed
GET  ./feed/update/<post>/               one post with its comments
POST ./posts/<post>/<action>             like_post, unlike_post, comment_post (field `text`)
GET  ./mynetwork/  ./mynetwork/invitations/  ./mynetwork/connections/
POST ./mynetwork/invitations/<verb>      accept | ignore (field `connection_id`)
GET  ./jobs/?filter=&q=&job=             job list and the open posting (requirements)
POST ./jobs/<job>/apply
GET  ./messaging/?filter=&q=&conversation=   threads; opening one marks it read
POST ./messaging/<conversation>/send     field `content`
POST ./messaging/new                     field `user_id`: the thread with that person
GET  ./notifications/?filter=
POST ./notifications/read                field `notification_id`, then to what it is about
GET  ./in/<user>/   POST ./in/<user>/sections   GET ./company/<company>/   GET ./search/?q=&kind=
"""

from django.urls import path

from apps.microdin import views

urlpatterns = [
    path("", views.feed, name="feed"),
    path("feed/update/<str:post_id>/", views.post, name="post"),
    path("posts/<str:post_id>/<str:action>", views.post_action, name="post-action"),
    path("mynetwork/", views.my_network, name="network"),
    path("mynetwork/invitations/", views.invitations, name="invitations"),
    path("mynetwork/connections/", views.connections, name="connections"),
    path("mynetwork/invitations/<str:verb>", views.answer_invitation, name="answer"),
    path("jobs/", views.jobs, name="jobs"),
    path("jobs/<str:job_id>/apply", views.apply, name="apply"),
    path("messaging/", views.messaging, name="messaging"),
    path("messaging/new", views.start_conversation, name="start-conversation"),
    path("messaging/<str:conversation_id>/send", views.send_message, name="send"),
    path("notifications/", views.notifications, name="notifications"),
    path("notifications/read", views.read_notification, name="read-notification"),
    path("in/<str:user_id>/", views.profile, name="profile"),
    path("in/<str:user_id>/sections", views.add_section, name="add-section"),
    path("company/<str:company_id>/", views.company, name="company"),
    path("search/", views.search, name="search"),
]
