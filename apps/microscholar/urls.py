"""MicroScholar pages, mounted by the core under /r/<token>/microscholar/.

GET  ./?q=&as_ylo=&as_yhi=&sort=&start=      home (recommended articles) or search results
GET  ./papers/<id>                            a paper: abstract, actions, related articles
GET  ./papers/<id>/cite                       the Cite dialog (opening it cites the paper)
GET  ./papers/<id>/export/<format>            bibtex | endnote | refman | refworks file
GET  ./citations?user=<id>&sortby=            a scholar's profile
GET  ./library                                saved papers
GET  ./alerts?filter=                         alerts
POST ./library/save, ./library/remove         field paper_id (+ back)
POST ./alerts/read                            field alert_id (+ back)
"""

from django.urls import path

from apps.microscholar import views

urlpatterns = [
    path("", views.search, name="search"),
    path("papers/<str:paper_id>", views.paper, name="paper"),
    path("papers/<str:paper_id>/cite", views.cite, name="cite"),
    path("papers/<str:paper_id>/export/<str:fmt>", views.export, name="export"),
    path("citations", views.profile, name="profile"),
    path("library", views.library, name="library"),
    path("library/save", views.save, name="save"),
    path("library/remove", views.remove, name="remove"),
    path("alerts", views.alerts, name="alerts"),
    path("alerts/read", views.mark_alert_read, name="alert-read"),
]
