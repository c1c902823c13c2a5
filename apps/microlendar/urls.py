"""MicroLendar pages, mounted by the core under /r/<token>/microlendar/ (`token` is a URL kwarg).

GET      ./?view=&date=&q=&off=&event=    the calendar (opening an event marks it viewed)
GET/POST ./events/new?date=&time=&kind=   create an event (kind=reminder: a reminder)
GET/POST ./events/<id>/edit               edit an event
POST     ./events/<id>/reschedule         date, time (the form and a drag and drop)
POST     ./events/<id>/delete
POST     ./tasks/new                      title, dueDate
POST     ./tasks/<id>/toggle | delete
"""

from django.urls import path

from apps.microlendar import views

urlpatterns = [
    path("", views.calendar, name="calendar"),
    path("events/new", views.new_event, name="new-event"),
    path("events/<str:event_id>/edit", views.edit_event, name="edit-event"),
    path("events/<str:event_id>/<str:action>", views.event_action, name="event-action"),
    path("tasks/new", views.new_task, name="new-task"),
    path("tasks/<str:task_id>/<str:action>", views.task_action, name="task-action"),
]
