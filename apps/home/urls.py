from django.urls import path

from apps.home import views

urlpatterns = [
    path("", views.home, name="home"),
    path("browse/<str:environment>/", views.browse, name="home-browse"),
    path("docs/<str:name>/", views.doc, name="home-doc"),
]
