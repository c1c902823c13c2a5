"""MicroMail pages, mounted by the core under /r/<token>/micromail/ (`token` is a URL kwarg).

GET  ./?folder=&filter=&q=&scope=&email=   the mail client (opening an email marks it read)
     &preview=<attachment id>              an attachment of the open email, over the page
GET  ./compose?mode=&email=                compose: new, reply, reply_all, forward, draft
POST ./compose                             send, save_draft, discard (confirm), discard_confirmed,
                                           edit (field `intent`)
POST ./emails/<id>/<action>                mark_read, mark_unread, flag, unflag, pin, unpin,
                                           move (field `folder`), delete
POST ./bulk                                the same actions for every checked `ids`
POST ./favorites                           add_favorite, remove_favorite (fields `action`, `folder`)
"""

from django.urls import path

from apps.micromail import views

urlpatterns = [
    path("", views.mailbox, name="mailbox"),
    path("compose", views.compose, name="compose"),
    path("bulk", views.bulk_action, name="bulk"),
    path("favorites", views.favorite_action, name="favorites"),
    path("emails/<str:email_id>/<str:action>", views.email_action, name="email-action"),
]
