"""MicroHood pages, mounted by the core under /r/<token>/microhood/.

GET  ./?range=                       Investing: portfolio value and chart, buying power, news,
                                     the Stocks / Lists sidebar
GET  ./stocks/<symbol>?range=&side=  a stock: price chart, about, position, order ticket
POST ./stocks/<symbol>/order         place_order (side, type, quantity, limit_price)
POST ./stocks/<symbol>/watch         add_to_watchlist / remove_from_watchlist (field `intent`)
GET  ./market                        equity and crypto cards
GET  ./watchlist                     the list, with remove buttons
GET  ./news                          every story, newest first
GET  ./orders                        order history; POST ./orders/cancel cancels a resting order
GET  ./search?q=                     symbol or company name
"""

from django.urls import path

from apps.microhood import views

app_name = "microhood"

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
