"""MicroHub pages, mounted by the core under /r/<token>/microhub/ (`token` is a URL kwarg).

GET  ./  ./tree/<path>  ./blob/<path>  ./commits/        code, folders, files, history
GET  ./issues/?state=&q=&sort=   ./issues/<id>            issues list and one issue (viewed)
GET/POST ./issues/new                                     new issue
POST ./issues/<id>/<verb>                                 comment (field body), close, reopen
GET  ./pulls/?state=   ./pulls/<id>                       pull requests
POST ./pulls/<id>/<verb>                                  comment (body), merge (strategy)
GET  ./actions/?workflow=   ./actions/runs/<id>           workflow runs
POST ./repo/<verb>                                        star, unstar, watch, unwatch, fork
GET/POST ./settings   ./new      GET ./repositories/      settings, new repository, yours
GET/POST ./users/<username>                               profile; follow / unfollow
"""

from django.urls import path

from apps.microhub import views

urlpatterns = [
    path("", views.code, name="code"),
    path("tree/<path:path>", views.code, name="tree"),
    path("blob/<path:path>", views.blob, name="blob"),
    path("commits/", views.commits, name="commits"),
    path("issues/", views.issues, name="issues"),
    path("issues/new", views.new_issue, name="new-issue"),
    path("issues/<str:issue_id>", views.issue, name="issue"),
    path("issues/<str:issue_id>/<str:verb>", views.issue_action, name="issue-action"),
    path("pulls/", views.pulls, name="pulls"),
    path("pulls/<str:pr_id>", views.pull, name="pull"),
    path("pulls/<str:pr_id>/<str:verb>", views.pull_action, name="pull-action"),
    path("actions/", views.actions, name="actions"),
    path("actions/runs/<str:run_id>", views.run, name="run"),
    path("repo/<str:verb>", views.repo_action, name="repo-action"),
    path("settings", views.settings, name="settings"),
    path("new", views.new_repository, name="new-repository"),
    path("repositories/", views.repositories, name="repositories"),
    path("users/<str:username>", views.profile, name="profile"),
]
