"""MicroHood pages, mounted by the core under /r/<token>/microhood/ (README: Pages)."""

from django.urls import path

from apps.microhood import views

urlpatterns = [
    path("", views.home, name="home"),
    path("stocks/<str:symbol>", views.stock, name="stock"),
    path("stocks/<str:symbol>/order", views.place_order, name="order"),
    path("stocks/<str:symbol>/watch", views.watch_stock, name="watch"),
    path("market", views.market, name="market"),
    path("watchlist", views.watchlist, name="watchlist"),
    path("news", views.news, name="news"),
    path("orders", views.orders, name="orders"),
    path("orders/cancel", views.cancel_order, name="cancel-order"),
    path("search", views.search, name="search"),
]
